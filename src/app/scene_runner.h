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


  // Runs `scene` (read from `file`) into `directory` (created; earlier frames removed).
  // `observer` sees the state at every output time.
  RunOutcome
  run_loaded_scene(Scene                             &scene,
                   const std::string                 &file,
                   const std::string                 &directory,
                   ConditionalOStream                &pcout,
                   const OutputWriter::FrameObserver &observer = {});

  // The 'Time/Integrator' name of an integrator.
  std::string
  integrator_name(const Integrator integrator);
} // namespace clothsim
