#include "solvers/blas_kernels.h"

#include <dlfcn.h>
#include <strings.h>

#include <cstdlib>
#include <sstream>

namespace clothsim
{
  namespace
  {
    // OpenBLAS' entry points, looked up in the loaded libraries (absent where the BLAS is
    // another library): its configuration ("OpenBLAS 0.3.21 DYNAMIC_ARCH ... Prescott
    // ..."), the name of the kernels in use, and the pair that drops and redoes the
    // kernel choice (the latter reads OPENBLAS_CORETYPE).
    struct OpenBlas
    {
      using Text   = char *(*)();
      using Action = void (*)();
      Text config  = reinterpret_cast<Text>(dlsym(RTLD_DEFAULT, "openblas_get_config"));
      Text corename =
        reinterpret_cast<Text>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
      Action quit =
        reinterpret_cast<Action>(dlsym(RTLD_DEFAULT, "gotoblas_dynamic_quit"));
      Action init =
        reinterpret_cast<Action>(dlsym(RTLD_DEFAULT, "gotoblas_dynamic_init"));

      bool
      loaded() const
      {
        return config != nullptr && corename != nullptr;
      }
    };

    // The best kernels of OpenBLAS 0.3.21 this CPU runs, by its instruction sets (libgcc
    // checks that the operating system saves the AVX and AVX-512 registers); nullptr for
    // one with neither AVX-512 nor AVX2 with FMA.
    const char *
    best_kernels()
    {
      __builtin_cpu_init();
      if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
          __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
          __builtin_cpu_supports("avx512vl"))
        return "SkylakeX";
      if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
        return "Haswell";
      return nullptr;
    }
  } // namespace


  bool
  select_blas_kernels()
  {
    const OpenBlas blas;
    if (!blas.loaded() || blas.quit == nullptr || blas.init == nullptr ||
        std::getenv("OPENBLAS_CORETYPE") != nullptr ||
        strcasecmp(blas.corename(), "Prescott") != 0)
      return false;
    const char *kernels = best_kernels();
    if (kernels == nullptr || setenv("OPENBLAS_CORETYPE", kernels, 0) != 0)
      return false;
    blas.quit();
    blas.init();
    // Not kept: a child process (gmsh, an mpirun of a study) chooses for itself.
    unsetenv("OPENBLAS_CORETYPE");
    return true;
  }


  bool
  avx512_blas_kernels()
  {
    const OpenBlas blas;
    if (!blas.loaded())
      return false;
    for (const char *family : {"SkylakeX", "Cooperlake", "SapphireRapids"})
      if (strcasecmp(blas.corename(), family) == 0)
        return true;
    return false;
  }


  std::string
  blas_description(const bool selected)
  {
    const OpenBlas blas;
    if (!blas.loaded())
      return "BLAS: not OpenBLAS";
    std::istringstream config(blas.config());
    std::string        name, version;
    config >> name >> version;
    // A choice made in the environment is named as such: it may be narrower than what
    // OpenBLAS would pick (Haswell's kernels on an AVX-512 CPU; README, "OpenBLAS'
    // kernels").
    const char *environment = std::getenv("OPENBLAS_CORETYPE");
    return name + " " + version + " (" + blas.corename() + " kernels" +
           (selected      ? ", chosen by clothsim over OpenBLAS' Prescott"
            : environment ? std::string(", OPENBLAS_CORETYPE=") + environment
                          : std::string()) +
           ")";
  }
} // namespace clothsim
