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
//
// An isolated singleton's session directory is always
// <tmpdir>/ompi.<host>.<uid>/jf.0/1/0, the same for every such process of a user, and
// each removes it when it ends: a run that starts while another ends can find its
// directory removed halfway and fail in MPI_Init
// ("A call to mkdir was unable to create the desired directory", seen in CI with two runs
// at once). So an isolated process also gets a session base of its own,
// `orte_tmpdir_base` = a new directory ${TMPDIR:-/tmp}/clothsim-mpi.XXXXXX, removed after
// MPI_Finalize (unless the user set the base).

#include <deal.II/base/mpi.h>

#include <string>

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
      ~Preparation();
      bool        set_isolated = false;
      bool        set_pml      = false;
      std::string session_base; // the private session base made, or "" if none
    } preparation;
    dealii::Utilities::MPI::MPI_InitFinalize mpi;
  };
} // namespace clothsim
