#pragma once

// Rigid obstacles for contact. Each shape is a convex core inflated by a radius r, so its
// signed distance is d(y) = |y - q(y)| - r with q(y) the core's point closest to y:
//   point   (sphere of radius r),
//   segment (capsule: a cylinder with hemispherical ends),
//   disc    (a flat round table top with rounded rim; r = half its thickness),
//   box     (a box with edges rounded by r),
// and the half-space below a plane, d(y) = n·(y - c). Outside the core, d is convex and
// its Hessian positive semi-definite (distance to a convex set). Shapes are given in a
// body frame; a rigid motion x = R(t) (y - c) + c + T(t) (rotation by an angle θ(t) about
// a fixed axis through the shape's centre c, then a translation) places them in the
// world. A triangle-mesh obstacle moves the same way; its contact is by pairs of
// primitives (physics/obstacle_surface.h). The cloth's vertices meet a shape through d;
// with edge contact, its edges and triangles also meet the core's features (the
// sphere's centre, the capsule's segment, the box's corners and edges, the disc's rim as
// a polygon around the circle; core_features(), given as the shape's surface) by the
// same pairs, their distances less r.

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include "physics/obstacle_surface.h"

#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <string>

namespace clothsim::physics
{
  using namespace dealii;

  enum class ObstacleCore
  {
    half_space,
    point,
    segment,
    disc,
    box,
    mesh // a triangle surface: contact by primitive pairs, no signed distance
  };

  struct ObstacleShape
  {
    ObstacleCore core = ObstacleCore::half_space;
    Point<3>     center; // plane: a point on it; else the core's centre, m
    Tensor<1, 3> axis;   // unit: the plane's outer normal, the segment's or disc's axis
    double       half_length = 0.;                  // segment, m
    double       disc_radius = 0.;                  // disc, m
    Tensor<1, 3> half_extents;                      // box, along the body axes, m
    double       radius = 0.;                       // r, m (0 for the plane)
    std::shared_ptr<const ObstacleSurface> surface; // mesh, or the core's features
  };

  // The core's sharp features in the body frame as a surface of vertices and edges (no
  // triangles: a flat face cannot pass between the cloth's vertices): a point, a
  // segment, a box's 8 corners and 12 edges, a disc's rim as a polygon around the
  // circle whose corners lie within `tolerance` (m) of it. None for a plane or a mesh.
  std::shared_ptr<const ObstacleSurface>
  core_features(const ObstacleShape &shape, const double tolerance);

  // A signed distance (m) with its gradient (unit outside the core) and Hessian.
  struct SignedDistance
  {
    double       value = 0.;
    Tensor<1, 3> gradient;
    Tensor<2, 3> hessian;
  };

  // d at y in the body frame; derivatives only if `derivatives`.
  SignedDistance
  signed_distance(const ObstacleShape &shape, const Point<3> &y, const bool derivatives);

  // x = rotation y + translation; `present` false once the obstacle has left the scene
  // (Obstacle::pose): no distance, cap or pair then.
  struct RigidPose
  {
    Tensor<2, 3> rotation;
    Tensor<1, 3> translation;
    bool         present = true;

    Point<3>
    to_world(const Point<3> &y) const
    {
      return Point<3>(rotation * y + translation);
    }
    Point<3>
    to_body(const Point<3> &x) const
    {
      return Point<3>(transpose(rotation) * (x - translation));
    }
  };

  class Obstacle
  {
  public:
    // `translation(t)` (m) and `angle(t)` (rad, about `rotation_axis` through the
    // shape's centre); friction: Coulomb's μ against the cloth. The obstacle leaves the
    // scene after `removal_time` (s): its pose at a later time is not present.
    Obstacle(const std::string                        &name,
             const ObstacleShape                      &shape,
             const double                              friction,
             std::function<Tensor<1, 3>(const double)> translation,
             const Tensor<1, 3>                       &rotation_axis,
             std::function<double(const double)>       angle,
             const double removal_time = std::numeric_limits<double>::infinity());

    const std::string &
    name() const
    {
      return obstacle_name;
    }
    double
    friction() const
    {
      return friction_coefficient;
    }
    const ObstacleShape &
    shape() const
    {
      return body_shape;
    }

    RigidPose
    pose(const double t) const;

    // d and its world-frame derivatives at the world point x, the obstacle at `pose`
    // (+inf, derivatives zero, where the pose is not present).
    SignedDistance
    distance(const RigidPose &pose, const Point<3> &x, const bool derivatives) const;

    // The largest α in [0, 1] such that d(x + s dx) >= fraction d(x) for all s in
    // [0, α] (0 < fraction < 1, d(x) > 0): the line search's cap (continuous collision
    // detection along a straight path, obstacle at `pose`; 1 where it is not present).
    // Conservative: d along the
    // path is convex for every shape, so after its minimum on [0, 1] is located the first
    // crossing is bracketed and bisected, and the lower end of the bracket is returned.
    double
    step_bound(const RigidPose    &pose,
               const Point<3>     &x,
               const Tensor<1, 3> &dx,
               const double        fraction) const;

    // The smallest d over the triangle with corners x (world frame), the obstacle at
    // `pose`, to within `tolerance` (m; from above): between its corners a triangle can
    // come closer than they do, e.g. to a sphere or rod narrower than the triangle. The
    // signed distance of a convex set is convex, and so is its minimum over one
    // barycentric coordinate: nested golden-section searches. Exact for a sphere and a
    // capsule: the distance of the triangle from the core's point or segment, less the
    // radius. +inf where the pose is not present.
    double
    triangle_distance(const RigidPose               &pose,
                      const std::array<Point<3>, 3> &x,
                      const double                   tolerance) const;

  private:
    const std::string                         obstacle_name;
    const ObstacleShape                       body_shape;
    const double                              friction_coefficient;
    std::function<Tensor<1, 3>(const double)> translation;
    const Tensor<1, 3>                        rotation_axis; // unit
    std::function<double(const double)>       angle;
    const double                              removal_time;
  };
} // namespace clothsim::physics
