#pragma once

// Checkpoint and restart of a run (README.md, "Checkpoint and restart"). A run writes
// checkpoint.bin into its output directory (time/time_stepper_checkpoint.cc); each holds,
// besides the state, the run's parameters (ShortPRM text) and the directory its relative
// paths are relative to (the parameter file's). `clothsim --restart DIR` reads
// DIR/parameters.prm and the checkpoint, refuses any change but the end time and the
// output-only entries, checks that the mesh and partition are the checkpoint's, and
// continues the run into DIR.

#include <deal.II/base/conditional_ostream.h>

#include "io/checkpoint.h"
#include "scene/scene.h"

#include <string>
#include <vector>

namespace clothsim
{
  // Whether a run with these parameters writes checkpoints: the implicit integrators,
  // without self-contact (whose tangent's couplings grow over a run and are not stored).
  bool
  supports_checkpoints(const Parameters &parameters);

  // The run's records in each of its checkpoints: its parameters and the directory of
  // its parameter file (absolute).
  io::CheckpointData
  checkpoint_record(const Scene &scene);

  // clothsim --restart DIR [--set ...]: continues the run in `directory` from its
  // checkpoint. Returns the exit code (0, or 2 if the run fails); throws InputError on
  // bad input (a missing or corrupt checkpoint, a change other than the allowed ones)
  // before anything is written, Interrupted and io::OutputError as a run does.
  int
  run_restart(const std::string              &directory,
              const std::vector<std::string> &overrides,
              const MPI_Comm                  communicator,
              ConditionalOStream             &pcout);
} // namespace clothsim
