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
  // The settings obstacle contact and self-contact share: thickness, barrier stiffness
  // (adaptive or not), friction's static slip velocity.
  physics::ContactSettings
  contact_settings(const ContactParameters &parameters);

  std::vector<physics::Obstacle>
  make_obstacles(const ContactParameters &parameters, const std::string &parameter_file);

  // The farthest any of an analytic obstacle's core features (its ObstacleShape::surface)
  // moves between its poses at consecutive times k dt, k = 0, 1, ..., up to `end_time`
  // or its removal (m; sampled at most 100,000 times, evenly); 0 without features.
  double
  largest_core_step(const physics::Obstacle &obstacle,
                    const double             time_step,
                    const double             end_time);

  // The longest time step a run may take (s): 'Time step', and with adaptive steps
  // 'Maximum time step' if that is longer.
  double
  longest_time_step(const TimeParameters &time);

  // Per obstacle, whether its edge contact pairs take the projected exact tangent
  // ('Contact/Edge contact tangent'; 'automatic': where largest_core_step at the run's
  // longest_time_step exceeds half the obstacle's radius).
  std::vector<bool>
  projected_exact_pairs(const ContactParameters              &parameters,
                        const std::vector<physics::Obstacle> &obstacles,
                        const TimeParameters                 &time);

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
