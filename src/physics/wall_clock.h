#pragma once

// Wall-clock seconds for the timings that TimerOutput does not take: the assembly's
// estimate per term (physics/model.cc) and self-contact's phases.

#include <chrono>

namespace clothsim::physics
{
  using WallClock = std::chrono::steady_clock;

  // Seconds from `start` to now.
  inline double
  seconds_since(const WallClock::time_point start)
  {
    return std::chrono::duration<double>(WallClock::now() - start).count();
  }
} // namespace clothsim::physics
