#pragma once

// One run of a loaded scene, as the clothsim executable and its study drivers (model
// comparison, convergence study, speed-accuracy sweep) do it: the output directory is
// prepared, the header printed, the time loop run, the summary printed. A failed run
// (SimulationError) keeps everything written so far and is reported, not thrown.

#include <deal.II/base/conditional_ostream.h>

#include "io/output_writer.h"
#include "scene/scene.h"
#include "time/time_stepper.h"

#include <string>

namespace clothsim
{
  // What one run did.
  struct RunOutcome
  {
    RunSummary  summary;
    double      wall_seconds = 0.;
    bool        completed    = false;
    std::string failure;
  };


  // Checkpoints and restarts (app/restart.h).
  struct RunOptions
  {
    // Write checkpoints: every 'Output/Checkpoint interval' and when interrupted.
    bool checkpoints = false;
    // A restart: the checkpoint's run section and this rank's (io/checkpoint.h).
    const io::CheckpointData *resume_run  = nullptr;
    const io::CheckpointData *resume_rank = nullptr;
  };

  // Runs `scene` (read from `file`) into `directory` (created; earlier frames removed;
  // a restart continues the files there instead). `observer` sees the state at every
  // output time.
  RunOutcome
  run_loaded_scene(Scene                             &scene,
                   const std::string                 &file,
                   const std::string                 &directory,
                   ConditionalOStream                &pcout,
                   const OutputWriter::FrameObserver &observer = {},
                   const RunOptions                  &options  = {});

  // The 'Time/Integrator' name of an integrator.
  std::string
  integrator_name(const Integrator integrator);
} // namespace clothsim
