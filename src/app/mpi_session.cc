#include "app/mpi_session.h"

#include <cstdlib>

namespace clothsim
{
  namespace
  {
    constexpr const char *isolated_variable = "OMPI_MCA_ess_singleton_isolated";
    constexpr const char *pml_variable      = "OMPI_MCA_pml";

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
  } // namespace


  MpiSession::Preparation::Preparation()
  {
    if (started_by_launcher())
      return;
    set_isolated = set_if_unset(isolated_variable, "1");
    set_pml      = set_if_unset(pml_variable, "ob1");
  }


  MpiSession::MpiSession(int &argc, char **&argv)
    : mpi(argc, argv, 1)
  {
    if (preparation.set_isolated)
      unsetenv(isolated_variable);
    if (preparation.set_pml)
      unsetenv(pml_variable);
  }
} // namespace clothsim
