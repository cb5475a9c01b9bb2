#pragma once

// Everything a run writes into its output directory while it runs: solution.pvd with one
// solution-NNNNN.vtu (.pvtu plus one piece per rank under MPI) per output time,
// probes.csv and statistics.csv. Files are flushed as they are written, and solution.pvd
// is replaced atomically, so a run that stops early leaves a consistent record of
// everything up to that point.

#include <deal.II/base/conditional_ostream.h>

#include "scene/cloth_model.h"

#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace clothsim
{
  // One row of statistics.csv.
  struct StepStatistics
  {
    unsigned int step;
    double       time; // s (load factor in static mode)
    double       dt;   // s
    unsigned int newton_iterations;
    unsigned int linear_iterations;
    double       residual;              // final Newton residual 2-norm, N
    unsigned int retries;               // step halvings before this step was accepted
    Energies     energies;              // J
    double       wall_seconds;          // since the run started
    unsigned int rejected         = 0;  // steps rejected by the error control before it
    double       error_estimate   = 0.; // local error estimate of the step, m (0: none)
    double       assembly_seconds = 0.; // wall time of the step spent assembling
    double       linear_solve_seconds = 0.; // ... in linear solves and preconditioners
  };

  class OutputWriter
  {
  public:
    OutputWriter(const std::string                &directory,
                 const ClothModel                 &model,
                 const std::vector<ProbeLocation> &probes,
                 const bool                        write_vtk);

    // VTK frame (if enabled) and probe rows for the state (u, v), both ghosted.
    void
    write_state(const unsigned int step,
                const double       time,
                const VectorType  &u,
                const VectorType  &v);

    void
    write_statistics(const StepStatistics &row);

    // Called with every written state (time, ghosted displacement), e.g. to compare runs.
    using FrameObserver = std::function<void(const double time, const VectorType &u)>;
    void
    set_frame_observer(const FrameObserver &observer)
    {
      frame_observer = observer;
    }

  private:
    void
    write_vtk_frame(const double time, const VectorType &u, const VectorType &v);

    const std::string                           directory;
    const ClothModel                           &model;
    const std::vector<ProbeLocation>            probes;
    const bool                                  write_vtk;
    const bool                                  is_root;
    std::ofstream                               probes_csv;
    std::ofstream                               statistics_csv;
    std::vector<std::pair<double, std::string>> frames;
    FrameObserver                               frame_observer;
  };
} // namespace clothsim
