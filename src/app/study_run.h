#pragma once

// One run of a study (convergence study, speed-accuracy sweep): the scene loaded with
// the study's overrides, run quietly into its own directory, and its final state kept
// for comparison with other runs, possibly on other meshes: every vertex's reference
// position and displacement, and each probe's displacement. Comparisons between runs
// are made on the vertices they share (global refinement keeps the coarse vertices).

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include "io/parameters.h"
#include "time/time_stepper.h"

#include <array>
#include <string>
#include <vector>

namespace clothsim
{
  using namespace dealii;

  struct StudyRun
  {
    std::vector<std::string> overrides; // what distinguishes this run
    bool                     completed = false;
    std::string              failure;           // why it stopped, if it did
    double                   wall_seconds = 0.; // the time loop's, s
    RunSummary               summary;
    types::global_dof_index  unknowns  = 0;
    double                   time_step = 0.; // s ('Time/Time step')
    double                   end_time  = 0.; // s, or the load factor in static mode
    // The last output state (at 'End time' if completed): every vertex (X, Y, Z, ux, uy,
    // uz), sorted by reference position; on rank 0 only.
    std::vector<std::array<double, 6>> vertices;
    std::vector<Probe>        probes; // the scene's probes (and their closed-form values)
    std::vector<Tensor<1, 3>> probe_displacements; // at the last output state, m
  };

  // Loads `file` with `overrides` and runs it into `directory`. Input errors throw
  // InputError; a failed simulation is returned (completed = false).
  StudyRun
  run_study_case(const std::string              &file,
                 const std::vector<std::string> &overrides,
                 const std::string              &directory,
                 const MPI_Comm                  communicator);

  // A value for a parameter assignment that reads back as the same double.
  std::string
  parameter_value(const double value);

  // Position differences |u_a - u_b| over the vertices both runs have, m.
  struct FieldDifference
  {
    double       largest = 0.;
    double       rms     = 0.;
    unsigned int common  = 0; // vertices compared
  };

  FieldDifference
  field_difference(const std::vector<std::array<double, 6>> &a,
                   const std::vector<std::array<double, 6>> &b);

  // `a`'s vertices that `b` has too, in `a`'s order, with b's displacements: b restricted
  // to a's mesh. Throws std::runtime_error if none are shared.
  std::vector<std::array<double, 6>>
  restrict_to(const std::vector<std::array<double, 6>> &b,
              const std::vector<std::array<double, 6>> &a);
} // namespace clothsim
