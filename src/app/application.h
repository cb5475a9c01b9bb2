#pragma once

// What the clothsim executable does: parse the command line and parameters, read and
// check the mesh, create the output directory only once all input is valid, run, report.

namespace clothsim
{
  // Returns the process exit code: 0 success, 1 bad input, 2 the simulation failed.
  int
  run_application(const int argc, const char *const *argv);
} // namespace clothsim
