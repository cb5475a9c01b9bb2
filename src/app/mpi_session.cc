#include "app/mpi_session.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace clothsim
{
  namespace
  {
    constexpr const char *isolated_variable = "OMPI_MCA_ess_singleton_isolated";
    constexpr const char *pml_variable      = "OMPI_MCA_pml";
    constexpr const char *base_variable     = "OMPI_MCA_orte_tmpdir_base";

    // A launcher's variables: OpenMPI's mpirun, PMIx, PMI-1/2 (MPICH, Slurm's srun).
    bool
    started_by_launcher()
    {
      for (const char *name :
           {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
        if (std::getenv(name) != nullptr)
          return true;
      return false;
    }

    // Sets `name` to `value` if it is unset; returns whether it did.
    bool
    set_if_unset(const char *name, const char *value)
    {
      if (std::getenv(name) != nullptr)
        return false;
      return setenv(name, value, 0) == 0;
    }

    // A new empty directory ${TMPDIR:-/tmp}/clothsim-mpi.XXXXXX, or "" if it cannot be
    // made (then OpenMPI uses its default base and reports its own errors).
    std::string
    make_private_directory()
    {
      const char *tmpdir = std::getenv("TMPDIR");
      std::string pattern =
        std::string(tmpdir != nullptr && *tmpdir != '\0' ? tmpdir : "/tmp") +
        "/clothsim-mpi.XXXXXX";
      std::vector<char> name(pattern.begin(), pattern.end());
      name.push_back('\0');
      return mkdtemp(name.data()) != nullptr ? std::string(name.data()) : std::string();
    }
  } // namespace


  MpiSession::Preparation::Preparation()
  {
    if (started_by_launcher())
      return;
    set_isolated = set_if_unset(isolated_variable, "1");
    set_pml      = set_if_unset(pml_variable, "ob1");
    if (set_isolated && std::getenv(base_variable) == nullptr)
      {
        session_base = make_private_directory();
        if (!session_base.empty() && setenv(base_variable, session_base.c_str(), 0) != 0)
          {
            rmdir(session_base.c_str());
            session_base.clear();
          }
      }
  }


  MpiSession::Preparation::~Preparation()
  {
    if (session_base.empty())
      return;
    std::error_code ignored; // best effort: what OpenMPI did not remove is left, harmless
    std::filesystem::remove_all(session_base, ignored);
  }


  MpiSession::MpiSession(int &argc, char **&argv)
    : mpi(argc, argv, 1)
  {
    if (preparation.set_isolated)
      unsetenv(isolated_variable);
    if (preparation.set_pml)
      unsetenv(pml_variable);
    if (!preparation.session_base.empty())
      unsetenv(base_variable);
  }
} // namespace clothsim
