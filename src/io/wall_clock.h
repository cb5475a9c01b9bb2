#pragma once

// Wall-clock seconds for the timings that TimerOutput does not take: the assembly's
// estimate per term (physics/model.cc), self-contact's phases and the progress line.

#include <chrono>

namespace clothsim::io
{
  using WallClock = std::chrono::steady_clock;

  // Seconds from `start` to now.
  inline double
  seconds_since(const WallClock::time_point start)
  {
    return std::chrono::duration<double>(WallClock::now() - start).count();
  }
} // namespace clothsim::io
