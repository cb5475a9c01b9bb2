#pragma once

// The side-by-side comparison of two runs of one scene (clothsim --compare): the finite
// element and the mass-spring model on the same mesh, matched frame by frame (output
// times) and vertex by vertex (reference positions). Writes into the comparison's
// directory:
//   comparison.csv  time,quantity,difference,relative_difference: per output time, the
//                   distance |x_fem - x_ms| (m) at each probe and over the whole mesh
//                   (quantity mesh_rms: root mean square over the vertices; mesh_max: the
//                   largest), relative to the sheet size (the reference mesh's largest
//                   bounding-box side)
//   runtimes.csv    model,integrator,time_step,steps,newton_iterations,wall_seconds,
//                   completed
//   comparison.png  each probe's displacement history in both models

#include "time/time_stepper.h"

#include <array>
#include <string>
#include <vector>

namespace clothsim
{
  // Every vertex (X, Y, Z, ux, uy, uz), sorted by reference position, and each probe's
  // displacement (interpolated, io/probe_location.h), at each output time.
  struct Trajectory
  {
    std::vector<double>                             times;
    std::vector<std::vector<std::array<double, 6>>> frames;
    std::vector<std::vector<Tensor<1, 3>>>          probes; // [frame][probe], m
  };

  struct ComparedRun
  {
    std::string model;      // "fem", "mass-spring"
    std::string integrator; // as in Time/Integrator
    double      time_step;  // s
    RunSummary  summary;
    double      wall_seconds;
    bool        completed; // false if the run stopped early (its frames up to then)
    Trajectory  trajectory;
  };

  struct ComparisonFigures
  {
    double       sheet_size;  // m
    unsigned int frames;      // compared output times
    double       final_rms;   // m, at the last compared time
    double       final_max;   // m
    double       largest_rms; // m, over all compared times
    double       largest_max; // m
  };

  // Writes the three files (on the calling rank: call on rank 0 only) and returns the
  // figures. `probe_names`: the probes of both trajectories, in their order.
  ComparisonFigures
  write_comparison(const std::string              &directory,
                   const ComparedRun              &fem,
                   const ComparedRun              &mass_spring,
                   const std::vector<std::string> &probe_names);
} // namespace clothsim
