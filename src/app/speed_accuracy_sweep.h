#pragma once

// clothsim --sweep: the speed-accuracy trade of one scene. Every combination of the
// sweep's axes (--axis "Section/Name=a | Section/Name=b & Other/Name=c": alternatives
// separated by '|', each one or more assignments joined by '&') is run, and so is a
// converged reference (--reference-set; by default the implicit midpoint rule with full
// Newton and the finite elements at an eighth of the smallest step of the grid, on the
// finest mesh of the grid). Each run's error is the largest distance |x - x_ref| at the
// end over the vertices it shares with the reference (m); its cost the wall time of its
// time loop (s), all measured in this one process, so the ratios hold. A run is on the
// Pareto front if no run is at least as fast and at least as accurate with one of the
// two strictly. Without --axis the grid is model (fem, mass-spring) x integrator
// (backward euler, bdf2, implicit midpoint) x step (2 dt, dt, dt/2 of the scene) x
// Newton method (newton, modified newton, single step), plus the implicit midpoint rule
// with an accuracy target of 1 mm for each model with newton and modified newton.
// Writes into the sweep's directory: run-NNN/ and reference/ (each run's output),
// pareto.csv (setting,runtime_seconds,error,rms_error,steps,newton_iterations,status,
// on_front; status: completed, failed, invalid input) and pareto.png (runtime against
// error, log-log, the front joined); prints the table and the fastest setting for each
// error level.

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include "app/command_line.h"

#include <string>
#include <vector>

namespace clothsim
{
  using namespace dealii;

  // The grid: every combination of one alternative per axis, each a list of
  // assignments. Throws InputError for an empty alternative or one without '='.
  std::vector<std::vector<std::string>>
  sweep_settings(const std::vector<std::string> &axes);

  // Returns the exit code: 0 if the reference completed, 2 otherwise.
  int
  run_speed_accuracy_sweep(const CommandLine  &command_line,
                           const std::string  &file,
                           const std::string  &directory,
                           const MPI_Comm      communicator,
                           ConditionalOStream &pcout);
} // namespace clothsim
