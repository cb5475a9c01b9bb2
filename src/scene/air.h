#pragma once

// The air term of a scene (physics/air_drag.h) from the section "Air": its properties,
// and the wind's expressions parsed once into a function of position and time.

#include "io/parameters.h"
#include "mesh/discretization.h"
#include "physics/air_drag.h"

#include <memory>
#include <string>

namespace clothsim
{
  // The air drag of `air` (density > 0). The wind is none (no evaluation) where all
  // three expressions are '0'. Throws InputError naming `parameter_file` and Air/Wind
  // for an expression that does not parse or is not finite at t = 0 at a triangle's
  // reference centroid. Collective.
  std::unique_ptr<physics::AirDrag>
  make_air_drag(const AirParameters        &air,
                const std::string          &parameter_file,
                const mesh::Discretization &discretization);
} // namespace clothsim
