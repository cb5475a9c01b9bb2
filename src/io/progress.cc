#include "io/progress.h"

#include <unistd.h>

#include <cstdio>
#include <iomanip>
#include <sstream>

namespace clothsim
{
  Progress::Progress(std::ostream &out, const std::string &mode, const bool active)
    : out(out)
    , enabled(active && mode != "off")
    , terminal(isatty(fileno(stdout)) != 0)
    , start(std::chrono::steady_clock::now())
  {
    if (mode == "auto" && !terminal)
      enabled = false;
  }


  void
  Progress::update(const double fraction, const std::string &state)
  {
    if (!enabled)
      return;
    const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double       eta = fraction > 0. ? elapsed * (1. - fraction) / fraction : 0.;
    std::ostringstream line;
    line << std::fixed << std::setprecision(1) << std::setw(5) << 100. * fraction << "%  "
         << state << "  elapsed " << elapsed << " s  ETA " << eta << " s";
    if (terminal)
      {
        out << '\r' << line.str() << "\033[K" << std::flush;
        line_open = true;
      }
    else if (fraction >= next_log_fraction)
      {
        out << line.str() << '\n' << std::flush;
        while (next_log_fraction <= fraction)
          next_log_fraction += 0.1;
      }
  }


  void
  Progress::finish()
  {
    if (line_open)
      out << '\n' << std::flush;
    line_open = false;
  }
} // namespace clothsim
