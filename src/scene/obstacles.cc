#include "scene/obstacles.h"

#include <deal.II/base/function_parser.h>

#include "io/input_error.h"
#include "mesh/surface_mesh.h"
#include "scene/boundary_conditions.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

namespace clothsim
{
  std::vector<physics::Obstacle>
  make_obstacles(const ContactParameters &parameters, const std::string &parameter_file)
  {
    std::vector<physics::Obstacle> obstacles;
    for (unsigned int k = 0; k < parameters.obstacles.size(); ++k)
      {
        const ObstacleParameters &given = parameters.obstacles[k];
        physics::ObstacleShape    shape;
        shape.center       = given.center;
        shape.axis         = given.axis / given.axis.norm();
        shape.radius       = given.radius;
        shape.half_length  = given.half_length;
        shape.disc_radius  = given.disc_radius;
        shape.half_extents = given.half_extents;
        shape.core         = given.shape == "mesh"     ? physics::ObstacleCore::mesh
                             : given.shape == "plane"  ? physics::ObstacleCore::half_space
                             : given.shape == "sphere" ? physics::ObstacleCore::point
                             : given.shape == "capsule" ? physics::ObstacleCore::segment
                             : given.shape == "disc"    ? physics::ObstacleCore::disc
                                                        : physics::ObstacleCore::box;
        if (shape.core == physics::ObstacleCore::half_space)
          shape.radius = 0.;
        if (shape.core == physics::ObstacleCore::mesh)
          {
            // Relative to the parameter file's directory.
            std::filesystem::path file = given.mesh_file;
            if (file.is_relative())
              file = std::filesystem::path(parameter_file).parent_path() / file;
            mesh::SurfaceMesh surface =
              mesh::read_surface_mesh(file.lexically_normal().string(), given.mesh_scale);
            shape.surface = std::make_shared<const physics::ObstacleSurface>(
              std::move(surface.vertices),
              std::move(surface.triangles),
              std::move(surface.edges));
          }
        else if (parameters.edge_contact)
          // The rim's chords within 1 % of the contact thickness of the circle.
          shape.surface = physics::core_features(shape, 1e-2 * parameters.thickness);

        // Expressions of t (x, y, z are there but 0: the motion is rigid).
        const std::string section     = "Obstacle " + std::to_string(k + 1);
        auto              translation = std::make_shared<FunctionParser<3>>(3);
        parse_vector_function(*translation,
                              given.translation,
                              true,
                              parameter_file,
                              section + "/Translation");
        auto angle = std::make_shared<FunctionParser<3>>(1);
        parse_vector_function(*angle,
                              given.rotation_angle,
                              true,
                              parameter_file,
                              section + "/Rotation angle");
        obstacles.emplace_back(
          given.name,
          shape,
          given.friction,
          [translation](const double t) {
            translation->set_time(t);
            Tensor<1, 3> value;
            for (unsigned int c = 0; c < 3; ++c)
              value[c] = translation->value(Point<3>(), c);
            return value;
          },
          given.rotation_axis,
          [angle](const double t) {
            angle->set_time(t);
            return angle->value(Point<3>());
          },
          given.removal_time);
      }
    return obstacles;
  }


  double
  largest_core_step(const physics::Obstacle &obstacle,
                    const double             time_step,
                    const double             end_time)
  {
    const auto &surface = obstacle.shape().surface;
    if (surface == nullptr || obstacle.shape().core == physics::ObstacleCore::mesh ||
        !(time_step > 0.))
      return 0.;
    // A rigid motion moves a body point y by (R' - R) y + (T' - T), affine in y: over the
    // features' convex hull its length is largest at one of their vertices.
    const double       steps   = std::ceil(end_time / time_step);
    const double       stride  = std::max(1., std::ceil(steps / 1e5));
    double             largest = 0.;
    physics::RigidPose before  = obstacle.pose(0.);
    for (double k = 0.; k < steps; k += stride)
      {
        const double             t     = k * time_step;
        const physics::RigidPose after = obstacle.pose(t + time_step);
        if (!after.present) // removed: its later motion moves nothing
          break;
        if (stride > 1.)
          before = obstacle.pose(t);
        for (const Point<3> &y : surface->vertices)
          largest = std::max(largest, before.to_world(y).distance(after.to_world(y)));
        before = after;
      }
    return largest;
  }


  double
  longest_time_step(const TimeParameters &time)
  {
    return time.adaptive_time_steps ? std::max(time.time_step, time.maximum_time_step)
                                    : time.time_step;
  }


  std::vector<bool>
  projected_exact_pairs(const ContactParameters              &parameters,
                        const std::vector<physics::Obstacle> &obstacles,
                        const TimeParameters                 &time)
  {
    std::vector<bool> result(obstacles.size(), false);
    for (unsigned int o = 0; o < obstacles.size(); ++o)
      result[o] =
        parameters.edge_contact_tangent == "projected exact" ||
        (parameters.edge_contact_tangent == "automatic" &&
         largest_core_step(obstacles[o], longest_time_step(time), time.end_time) >
           0.5 * obstacles[o].shape().radius);
    return result;
  }


  physics::ContactSettings
  contact_settings(const ContactParameters &given)
  {
    physics::ContactSettings settings{given.thickness,
                                      given.barrier_acceleration,
                                      given.slip_velocity};
    settings.stiffness = {given.adaptive_stiffness,
                          given.stiffening_distance * given.thickness,
                          given.max_barrier_acceleration / given.barrier_acceleration};
    return settings;
  }


  std::unique_ptr<physics::SelfContact>
  make_self_contact(const ContactParameters    &given,
                    const std::string          &parameter_file,
                    const mesh::Discretization &discretization,
                    const VectorType           &masses,
                    const VectorType           &initial)
  {
    auto term = std::make_unique<physics::SelfContact>(contact_settings(given),
                                                       discretization,
                                                       masses,
                                                       given.self_contact_full_pairs,
                                                       given.self_friction,
                                                       given.self_contact_creases);
    // The barrier must not act at rest, nor the cloth start through itself.
    VectorType rest;
    discretization.initialize_ghosted(rest);
    const double gap =
      term->report(rest, given.thickness, /*within_pieces=*/true).min_distance;
    if (gap < given.thickness)
      throw InputError(parameter_file,
                       "Contact/Thickness",
                       "the thickness " + std::to_string(given.thickness) +
                         " m exceeds the distance " + std::to_string(gap) +
                         " m between two of the cloth's primitives (vertex-triangle or "
                         "edge-edge, sharing no vertex, in one connected piece) at rest: "
                         "the barrier would push "
                         "them apart; choose a smaller thickness or a coarser mesh");
    if (term->report(initial, given.thickness).min_distance <= 0.)
      throw InputError(parameter_file,
                       "Contact/Self contact",
                       "the cloth's initial state touches or passes through itself");
    return term;
  }
} // namespace clothsim
