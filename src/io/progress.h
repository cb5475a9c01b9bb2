#pragma once

// Progress of a long run: on a terminal one updating line (step, simulated time, elapsed
// time, ETA); otherwise (a log file, a pipe, any run under an MPI launcher) a plain line
// every 5 % of the run, never a carriage return.

#include <chrono>
#include <ostream>
#include <string>

namespace clothsim
{
  class Progress
  {
  public:
    // mode (Output/Progress): "auto" (the updating line on a terminal, plain lines
    // otherwise), "lines" (plain lines always), "off". Only `active` ranks print.
    Progress(std::ostream &out, const std::string &mode, const bool active);
    // Ends an open line, also when a run stops with an exception.
    ~Progress()
    {
      finish();
    }

    // fraction in [0, 1] of the run done, with a short description of the state.
    void
    update(const double fraction, const std::string &state);
    // Ends the updating line, if one is open (before other output).
    void
    finish();

    // The fraction of the run between two plain lines.
    static constexpr double line_interval = 0.05;

    // Whether standard output is a terminal that shows an updating line: not under an
    // MPI launcher, whose ranks write to pseudo-terminals even when the launcher's own
    // output goes to a file.
    static bool
    updating_terminal();

  private:
    std::ostream                         &out;
    bool                                  enabled;
    bool                                  terminal;
    std::chrono::steady_clock::time_point start;
    double                                next_line_fraction = line_interval;
    bool                                  line_open          = false;
  };
} // namespace clothsim
