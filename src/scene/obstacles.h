#pragma once

// The scene's rigid obstacles (physics/obstacle.h) from the sections "Obstacle k".

#include "io/parameters.h"
#include "physics/obstacle.h"

#include <string>
#include <vector>

namespace clothsim
{
  // The obstacles in use, with their motions parsed; InputError naming `parameter_file`
  // and the entry for a bad expression.
  std::vector<physics::Obstacle>
  make_obstacles(const ContactParameters &parameters, const std::string &parameter_file);
} // namespace clothsim
