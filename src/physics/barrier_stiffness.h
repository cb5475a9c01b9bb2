#pragma once

// IPC's adaptive barrier stiffness (Li et al., "Incremental Potential Contact", ACM TOG
// 39(4), 2020, section 4.3), per contact term: the term's κ is scale × its given κ₀
// (m a_b / d̂). After each iterate Newton's line search accepts, the term reports the
// distance of its closest pair (over all ranks): while that is below the stiffening
// distance and below the closest distance of the previous iterate (or of the step's
// start), the scale doubles, up to a largest one. A barrier that balances a given force F
// at distance d balances it at a larger distance once stiffer (κ |s'(d)| = F, s'
// decreasing in magnitude with d), so pairs that forces drive towards round-off (where
// Newton's step cap stalls) are held farther apart. The scale is never lowered within an
// accepted step; an attempt of a step starts from the scale the last accepted step
// ended with (commit()), so what a failed attempt raised is taken back. A checkpoint
// keeps it (saved(), restore()).

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <vector>

namespace clothsim::physics
{
  struct StiffnessSettings
  {
    bool   adaptive  = false;
    double distance  = 0.; // the stiffening distance, m
    double max_scale = 1.; // the largest scale, >= 1
  };

  class AdaptiveStiffness
  {
  public:
    explicit AdaptiveStiffness(const StiffnessSettings &settings = {})
      : settings(settings)
    {}

    bool
    adaptive() const
    {
      return settings.adaptive;
    }
    // κ / κ₀.
    double
    scale() const
    {
      return current;
    }
    // Before each attempt of a step: the scale goes back to the last committed one, and
    // the closest pair's distance at the step's start (m, the same on every rank; +inf
    // if none is nearer than the stiffening distance) is recorded.
    void
    begin_attempt(const double closest)
    {
      current  = committed;
      previous = closest;
    }
    // The closest pair's distance at an accepted iterate (m, the same on every rank);
    // returns whether the scale changed.
    bool
    observe(const double closest)
    {
      const bool closing = closest < settings.distance && closest < previous;
      previous           = closest;
      if (!settings.adaptive || !closing || current >= settings.max_scale)
        return false;
      current = std::min(2. * current, settings.max_scale);
      ++n_raised;
      return true;
    }
    // The scale of the last accepted step.
    double
    committed_scale() const
    {
      return committed;
    }
    // After an accepted step: its scale is where the next attempts start.
    void
    commit()
    {
      committed = current;
    }
    // How many times the scale was raised in this run (since a restart, too; raises
    // taken back included).
    unsigned int
    raised() const
    {
      return n_raised;
    }

    // What a checkpoint keeps: the committed scale if adaptive (what the next attempt
    // starts from, also between a failed attempt and its retry), else nothing.
    std::vector<double>
    saved() const
    {
      return settings.adaptive ? std::vector<double>{committed} : std::vector<double>{};
    }
    void
    restore(const std::vector<double> &state)
    {
      if (state.size() != 1 || !(state[0] >= 1.))
        throw std::runtime_error("a checkpoint's barrier stiffness scale is not one "
                                 "number >= 1");
      current   = state[0];
      committed = state[0];
    }

  private:
    StiffnessSettings settings;
    double            current   = 1.;
    double            committed = 1.; // at the last accepted step's end
    double            previous  = std::numeric_limits<double>::infinity();
    unsigned int      n_raised  = 0;
  };
} // namespace clothsim::physics
