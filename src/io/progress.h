#pragma once

// Progress of a long run: one updating line on a terminal (step, simulated time, ETA), or
// a plain line every tenth of the run when the output goes to a log.

#include <chrono>
#include <ostream>
#include <string>

namespace clothsim
{
  class Progress
  {
  public:
    // mode: "auto" (updating line only on a terminal), "on", "off". Only `active` ranks
    // print.
    Progress(std::ostream &out, const std::string &mode, const bool active);
    // Ends an open line, also when a run stops with an exception.
    ~Progress()
    {
      finish();
    }

    // fraction in [0, 1] of the run done, with a short description of the state.
    void
    update(const double fraction, const std::string &state);
    void
    finish();

  private:
    std::ostream                         &out;
    bool                                  enabled;
    bool                                  terminal;
    std::chrono::steady_clock::time_point start;
    double                                next_log_fraction = 0.1;
    bool                                  line_open         = false;
  };
} // namespace clothsim
