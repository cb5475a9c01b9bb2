#include "io/progress.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <sstream>

namespace clothsim
{
  bool
  Progress::updating_terminal()
  {
    // Open MPI, MPICH and the PMIx launchers (srun) set these in every rank.
    for (const char *variable : {"OMPI_COMM_WORLD_SIZE", "PMI_RANK", "PMIX_RANK"})
      if (std::getenv(variable) != nullptr)
        return false;
    return isatty(fileno(stdout)) != 0;
  }


  Progress::Progress(std::ostream &out, const std::string &mode, const bool active)
    : out(out)
    , enabled(active && mode != "off")
    , terminal(mode == "auto" && updating_terminal())
    , start(std::chrono::steady_clock::now())
  {}


  void
  Progress::update(const double fraction, const std::string &state)
  {
    if (!enabled)
      return;
    // Plain lines at 5 %, 10 %, ... (and the end); the updating line at every call.
    constexpr double round_off = 1e-9; // t/T of a step at 5 % may fall just short
    if (!terminal && fraction + round_off < next_line_fraction && fraction < 1.)
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
    else
      {
        out << line.str() << '\n' << std::flush;
        while (next_line_fraction <= fraction + round_off)
          next_line_fraction += line_interval;
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
