#pragma once

// clothsim --convergence: one parameter file run at successive mesh refinements
// ('Mesh/Global refinements' + 0..K, --space K) and/or step sizes ('Time/Time step' / 1,
// 2, ..., 2^K, --time K). Errors at the end of the run (static mode: full load):
//   probe:<name>       |u - u_ref| at each probe (m);
//   mesh_max, mesh_rms the largest and the root-mean-square |u - u_ref| over the
//                      vertices of the coarsest run (they survive refinement), m.
// The reference is the Richardson extrapolation of the three finest runs,
//   u_ref = u_K + (u_K - u_K-1) / (2^p - 1), p = log2(|u_K-2 - u_K-1| / |u_K-1 - u_K|)
// from the mesh_max differences, if 0.5 <= p <= 8; otherwise (or with two runs) the
// finest run itself. In a space study a probe with 'Output/Probe references' is measured
// against that closed form instead (in a time study the limit is the space-discrete
// solution, so the closed form does not apply). Observed orders log2(e_i-1 / e_i).
// Writes into the study's directory: space-N/ and time-N/ (each run's output),
// convergence.csv (study,level,size,unknowns,quantity,reference,error,observed_order;
// size: the mesh size relative to the coarsest, or dt in s) and convergence.png
// (log-log, one panel per study); prints deal.II ConvergenceTables.

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include "app/command_line.h"

#include <string>

namespace clothsim
{
  using namespace dealii;

  // Returns the exit code: 0 if every run completed, 2 otherwise (the table then holds
  // the completed runs).
  int
  run_convergence_study(const CommandLine  &command_line,
                        const std::string  &file,
                        const std::string  &directory,
                        const MPI_Comm      communicator,
                        ConditionalOStream &pcout);
} // namespace clothsim
