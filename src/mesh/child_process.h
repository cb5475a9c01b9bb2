#pragma once

// Running library code that may crash on bad input in a child process first. gmsh 4.8
// crashes (SIGSEGV, heap corruption) on some malformed .msh files instead of reporting
// them (tests/fuzz_inputs found five kinds); a crash in a child is seen by the parent and
// becomes an ordinary input error.

#include <functional>
#include <string>

namespace clothsim::mesh
{
  // Runs `work` in a forked child process and waits for it. If `work` throws an
  // InputError there, the same InputError is thrown here; if the child dies of a signal,
  // an InputError on `file` saying `what` crashed with that signal. Nothing the child
  // does to memory reaches this process; what it writes to files does.
  void
  run_in_child_process(const std::string           &file,
                       const std::string           &what,
                       const std::function<void()> &work);
} // namespace clothsim::mesh
