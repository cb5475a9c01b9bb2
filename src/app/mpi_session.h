#pragma once

// MPI for the lifetime of a program (deal.II's MPI_InitFinalize, one thread per process),
// started without the parts a single process cannot use.
//
// A program run without a launcher (no mpirun, srun, ...) is one process. OpenMPI would
// still start a daemon for it (the "singleton" orted) and load the UCX transport for
// peers it cannot have: 0.4 s of the 1 s start-up of every `clothsim` run on the
// development machine. So before MPI_Init, when no launcher's environment is present, the
// session sets OpenMPI's `ess_singleton_isolated = 1` (no daemon) and `pml = ob1`
// (shared-memory and self transports), unless the user set them; after MPI_Init it
// removes what it set, so child processes see the environment the user gave. Runs under a
// launcher are not touched. Other MPI implementations ignore these variables.

#include <deal.II/base/mpi.h>

namespace clothsim
{
  class MpiSession
  {
  public:
    MpiSession(int &argc, char **&argv);

  private:
    // Constructed after the environment is prepared (a base would come first).
    struct Preparation
    {
      Preparation();
      bool set_isolated = false;
      bool set_pml      = false;
    } preparation;
    dealii::Utilities::MPI::MPI_InitFinalize mpi;
  };
} // namespace clothsim
