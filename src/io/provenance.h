#pragma once

// Where a run's results come from: clothsim's version and git revision, the versions of
// the libraries that compute them, the MPI ranks, the date and the command line. Printed
// by `clothsim --version`, at the top of every run's log and as comments at the top of
// the run's parameters.prm.

#include <mpi.h>

#include <string>
#include <vector>

namespace clothsim::io
{
  // Keeps the command line and the start time of this process for provenance_lines();
  // call once at start-up.
  void
  record_invocation(const int argc, const char *const *argv);

  // Keeps the BLAS' name, version and kernels (solvers/blas_kernels) for
  // libraries_line(); call once at start-up, after choosing the kernels.
  void
  record_blas(const std::string &description);

  // "clothsim 0.18.0 (git 1a2b3c4d5e6f)"; "-dirty" after the revision when the build had
  // uncommitted changes.
  std::string
  version_line();

  // The versions of deal.II, Trilinos, MUMPS, gmsh, the MPI library and the BLAS (with
  // its kernels), on one line.
  std::string
  libraries_line();

  // The whole record, one fact per line, without line prefixes: version, libraries, the
  // date (UTC) and the number of MPI ranks, the command line (arguments quoted where they
  // hold spaces or quotes).
  std::vector<std::string>
  provenance_lines(const MPI_Comm communicator);
} // namespace clothsim::io
