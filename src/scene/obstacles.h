#pragma once

// The scene's contact set-up: its rigid obstacles (physics/obstacle.h) from the sections
// "Obstacle k", and self-contact (physics/self_contact.h) from section "Contact".

#include "io/parameters.h"
#include "mesh/discretization.h"
#include "physics/obstacle.h"
#include "physics/self_contact.h"

#include <memory>
#include <string>
#include <vector>

namespace clothsim
{
  // The obstacles in use, with their motions parsed; InputError naming `parameter_file`
  // and the entry for a bad expression.
  std::vector<physics::Obstacle>
  make_obstacles(const ContactParameters &parameters, const std::string &parameter_file);

  // Self-contact of the cloth of `discretization` (`masses`: owned lumped masses), after
  // checking that the thickness is below the distance between the cloth's primitives at
  // rest and that `initial` (ghosted, the initial displacement) does not touch itself;
  // InputError naming `parameter_file` otherwise.
  std::unique_ptr<physics::SelfContact>
  make_self_contact(const ContactParameters    &parameters,
                    const std::string          &parameter_file,
                    const mesh::Discretization &discretization,
                    const VectorType           &masses,
                    const VectorType           &initial);
} // namespace clothsim
