// Contact kernels and terms against finite differences and their invariants:
// 1. Signed distances of every obstacle shape (physics/obstacle.h), in a turned and moved
//    pose: |∇d| = 1 outside, ∇d and ∇²d against central differences (relative 1e-6)
//    at 200 points per shape between 1 mm and 30 cm outside.
// 2. The barrier s(d) and the friction f0 (physics/contact_potential.h): derivatives
//    against central differences; s is C² at d̂, f0 C¹ at ε.
// 3. The line search's cap (Obstacle::step_bound): on 300 paths per shape, many of them
//    straight through the obstacle, d stays at or above the fraction of its start along
//    the whole capped path (sampled at 2,000 points), and the cap is tight (the level is
//    reached within 1e-9 m of the path's end when the cap is below 1). A path through a
//    sphere is capped before the sphere.
// 4. The contact and friction terms of a sheet lying 2 mm above a sphere of radius 1 m
//    (5 vertices within the thickness; the N = 21
//    swing mesh): the step potential's gradient and Hessian against central differences
//    of the potential and of the gradient (relative 1e-5), friction in its static and
//    kinetic ranges.
// 5. Edge contact's geometry: a triangle's smallest signed distance
//    (Obstacle::triangle_distance) against the smallest of 5,151 points sampled on it,
//    100 triangles per shape (a sphere's and a capsule's, computed in closed form,
//    against nested golden-section searches to 1e-10, within 1e-9 m); the core's
//    features less r (physics::core_features) give
//    the signed distance where the closest point of the core is on them (every point of
//    a sphere's or a capsule's core: to 1e-12 m; a box's edges and corners: 1e-12 m; a
//    disc's rim, a polygon around the circle: its tolerance, 1e-5 m), and never more
//    than that less.
// 6. How far a core moves in a step (scene/obstacles.h, largest_core_step, which picks
//    edge contact's tangent): a translating sphere's centre by v dt, a turning box's
//    corners by the chord 2 ρ sin(ω dt/2), to 1e-12, a sphere removed at 0.5 s
//    ('Removed at') as it jumps 100 m by v dt (its motion up to then). 'automatic' takes
//    the projected exact tangent for the sphere moving by a quarter of its radius per
//    'Time step' only when adaptive steps may grow to 'Maximum time step' (4 times as
//    long).

#include "contact_checks.h"
#include "physics/contact_potential.h"
#include "scene/obstacles.h"

#include <random>

using namespace clothsim;
using namespace clothsim::test;
using physics::Obstacle;
using physics::ObstacleCore;
using physics::ObstacleShape;

namespace
{
  std::vector<Obstacle>
  shapes()
  {
    const auto still  = [](const double) { return Tensor<1, 3>(); };
    const auto moved  = [](const double t) { return Tensor<1, 3>({0.1 * t, -0.2, 0.3}); };
    const auto turned = [](const double t) { return 0.7 + t; };
    std::vector<Obstacle> result;
    ObstacleShape         shape;
    shape.center = Point<3>(0.1, -0.2, 0.05);
    shape.axis   = Tensor<1, 3>({0.2, 0.3, 1.}) / Tensor<1, 3>({0.2, 0.3, 1.}).norm();
    shape.core   = ObstacleCore::half_space;
    result.emplace_back("plane", shape, 0., moved, Tensor<1, 3>({1., 0., 0.}), turned);
    shape.core   = ObstacleCore::point;
    shape.radius = 0.2;
    result.emplace_back("sphere", shape, 0., moved, Tensor<1, 3>({0., 1., 1.}), turned);
    shape.core        = ObstacleCore::segment;
    shape.radius      = 0.05;
    shape.half_length = 0.3;
    result.emplace_back("capsule", shape, 0., moved, Tensor<1, 3>({1., 1., 0.}), turned);
    shape.core        = ObstacleCore::disc;
    shape.radius      = 0.01;
    shape.disc_radius = 0.25;
    result.emplace_back("disc", shape, 0., still, Tensor<1, 3>({0., 1., 0.}), turned);
    shape.core         = ObstacleCore::box;
    shape.radius       = 0.02;
    shape.half_extents = Tensor<1, 3>({0.3, 0.1, 0.2});
    result.emplace_back("box", shape, 0., moved, Tensor<1, 3>({0., 0., 1.}), turned);
    return result;
  }

  // A point between 1 mm and 30 cm outside the obstacle.
  Point<3>
  outside(const Obstacle &obstacle, const physics::RigidPose &pose, std::mt19937 &random)
  {
    std::uniform_real_distribution<double> box(-0.8, 0.8);
    for (;;)
      {
        const Point<3> x(box(random), box(random), box(random));
        const double   d = obstacle.distance(pose, x, false).value;
        if (d > 1e-3 && d < 0.3)
          return x;
      }
  }

  bool
  check_distances(ConditionalOStream &pcout)
  {
    bool         passed = true;
    std::mt19937 random(7);
    const double h = 1e-6;
    for (const Obstacle &obstacle : shapes())
      {
        const physics::RigidPose pose       = obstacle.pose(0.4);
        double                   unit_error = 0., gradient_error = 0., hessian_error = 0.;
        for (unsigned int sample = 0; sample < 200; ++sample)
          {
            const Point<3>                x = outside(obstacle, pose, random);
            const physics::SignedDistance d = obstacle.distance(pose, x, true);
            unit_error = std::max(unit_error, std::abs(d.gradient.norm() - 1.));
            for (unsigned int i = 0; i < 3; ++i)
              {
                Point<3> plus = x, minus = x;
                plus[i] += h;
                minus[i] -= h;
                const physics::SignedDistance dp = obstacle.distance(pose, plus, true);
                const physics::SignedDistance dm = obstacle.distance(pose, minus, true);
                gradient_error =
                  std::max(gradient_error,
                           std::abs((dp.value - dm.value) / (2. * h) - d.gradient[i]));
                const Tensor<1, 3> column = (dp.gradient - dm.gradient) / (2. * h);
                for (unsigned int j = 0; j < 3; ++j)
                  hessian_error = std::max(hessian_error,
                                           std::abs(column[j] - d.hessian[j][i]) /
                                             std::max(1., d.hessian.norm()));
              }
          }
        const std::string name = obstacle.name();
        passed &=
          check_below(pcout, name + ": largest ||grad d| - 1|", unit_error, 1e-12);
        passed &= check_below(pcout,
                              name + ": gradient against differences",
                              gradient_error,
                              1e-6);
        passed &=
          check_below(pcout, name + ": Hessian against differences", hessian_error, 1e-5);
      }
    return passed;
  }

  bool
  check_potentials(ConditionalOStream &pcout)
  {
    namespace contact  = physics::contact;
    const double d_hat = 0.005, epsilon = 2e-5, h = 1e-9;
    double       barrier_error = 0., friction_error = 0.;
    for (unsigned int k = 1; k < 100; ++k)
      {
        const double d  = d_hat * k / 100.;
        barrier_error   = std::max(barrier_error,
                                 std::abs((contact::barrier(d + h, d_hat) -
                                           contact::barrier(d - h, d_hat)) /
                                            (2. * h) -
                                          contact::barrier_first(d, d_hat)) /
                                   std::abs(contact::barrier_first(d, d_hat)));
        barrier_error   = std::max(barrier_error,
                                 std::abs((contact::barrier_first(d + h, d_hat) -
                                           contact::barrier_first(d - h, d_hat)) /
                                            (2. * h) -
                                          contact::barrier_second(d, d_hat)) /
                                   std::abs(contact::barrier_second(d, d_hat)));
        const double y  = 1.5 * epsilon * k / 100.;
        const double e  = 1e-12;
        const auto   f1 = [&](const double s) {
          return contact::friction_f1_over_y(s, epsilon) * s;
        };
        friction_error = std::max(friction_error,
                                  std::abs((contact::friction_f0(y + e, epsilon) -
                                            contact::friction_f0(y - e, epsilon)) /
                                             (2. * e) -
                                           f1(y)));
        if (std::abs(y - epsilon) > 2. * e)
          friction_error =
            std::max(friction_error,
                     epsilon * std::abs((f1(y + e) - f1(y - e)) / (2. * e) -
                                        contact::friction_f1_prime(y, epsilon)));
      }
    bool passed = check_below(pcout,
                              "barrier s', s'' against differences (relative)",
                              barrier_error,
                              1e-5);
    passed &=
      check_below(pcout, "friction f1, f1' against differences", friction_error, 1e-4);
    const double at_edge = std::abs(contact::barrier(d_hat * (1. - 1e-9), d_hat)) +
                           std::abs(contact::barrier_first(d_hat * (1. - 1e-9), d_hat)) +
                           std::abs(contact::barrier_second(d_hat * (1. - 1e-9), d_hat));
    passed &= check_below(pcout, "s, s', s'' just inside d̂", at_edge, 1e-7);
    passed &= check_near(pcout,
                         "f0(ε) (continuous)",
                         contact::friction_f0(epsilon * (1. - 1e-12), epsilon),
                         epsilon,
                         1e-15);
    passed &=
      check(pcout, !std::isfinite(contact::barrier(0., d_hat)), "s(0) is infinite");
    return passed;
  }

  bool
  check_step_bounds(ConditionalOStream &pcout)
  {
    bool                                   passed = true;
    std::mt19937                           random(11);
    std::uniform_real_distribution<double> direction(-1., 1.);
    const double                           fraction = 0.1;
    for (const Obstacle &obstacle : shapes())
      {
        const physics::RigidPose pose = obstacle.pose(0.4);
        double       worst = std::numeric_limits<double>::infinity(), slack = 0.;
        unsigned int capped = 0;
        for (unsigned int sample = 0; sample < 300; ++sample)
          {
            const Point<3> x  = outside(obstacle, pose, random);
            const double   d0 = obstacle.distance(pose, x, false).value;
            // Toward and past the obstacle, up to 1 m long.
            Tensor<1, 3> dx({direction(random), direction(random), direction(random)});
            const physics::SignedDistance closest = obstacle.distance(pose, x, true);
            dx -= (1.5 + 0.5 * direction(random)) * closest.gradient;
            dx *= 0.6;
            const double alpha = obstacle.step_bound(pose, x, dx, fraction);
            for (unsigned int k = 0; k <= 2000; ++k)
              worst = std::min(
                worst,
                obstacle.distance(pose, x + (alpha * k / 2000.) * dx, false).value / d0);
            if (alpha < 1.)
              {
                ++capped;
                slack = std::max(slack,
                                 obstacle.distance(pose, x + alpha * dx, false).value -
                                   fraction * d0);
              }
          }
        const std::string name = obstacle.name();
        pcout << "  " << name << ": " << capped << " of 300 paths capped" << std::endl;
        passed &= check_at_least(pcout,
                                 name + ": smallest d / d0 on the capped paths",
                                 worst,
                                 fraction * (1. - 1e-12));
        passed &=
          check_below(pcout, name + ": d - fraction d0 where capped, m", slack, 1e-9);
        passed &= check_above(pcout, name + ": paths capped", capped, 50);
      }
    // Straight through a sphere: the cap stops before it.
    ObstacleShape sphere;
    sphere.core   = ObstacleCore::point;
    sphere.radius = 0.1;
    const Obstacle ball(
      "ball",
      sphere,
      0.,
      [](double) { return Tensor<1, 3>(); },
      Tensor<1, 3>({0., 0., 1.}),
      [](double) { return 0.; });
    const physics::RigidPose pose  = ball.pose(0.);
    const double             alpha = ball.step_bound(pose,
                                         Point<3>(0., 0., 0.2),
                                         Tensor<1, 3>({0., 0., -0.5}),
                                         fraction);
    passed &= check_near(pcout,
                         "cap of a path through a sphere (d from 0.1 m to 0.01 m)",
                         alpha,
                         0.18,
                         1e-9);
    return passed;
  }

  // A sheet lying 2 mm above a sphere of radius 1 m (5 vertices within the thickness).
  bool
  check_terms(ConditionalOStream &pcout, const std::string &mesh)
  {
    physics::ObstacleShape shape;
    shape.core   = ObstacleCore::point;
    shape.center = Point<3>(0.5, 0.5, -1.002);
    shape.radius = 1.;
    std::vector<Obstacle> obstacles;
    obstacles.emplace_back(
      "ball",
      shape,
      0.4,
      [](double) { return Tensor<1, 3>(); },
      Tensor<1, 3>({0., 0., 1.}),
      [](double) { return 0.; });
    return check_contact_terms(pcout, mesh, obstacles, 1);
  }

  // The distance from y to the segment [a, b].
  double
  segment_distance(const Point<3> &y, const Point<3> &a, const Point<3> &b)
  {
    const Tensor<1, 3> e = b - a;
    const double       s = e.norm_square() > 0. ? (y - a) * e / e.norm_square() : 0.;
    return y.distance(a + std::clamp(s, 0., 1.) * e);
  }

  // The smallest value of a convex f on [lo, hi], by golden-section search to `step`.
  template <typename Function>
  double
  convex_min(const Function &f, double lo, double hi, const double step)
  {
    const double golden = 0.5 * (std::sqrt(5.) - 1.);
    double       m1 = hi - golden * (hi - lo), m2 = lo + golden * (hi - lo);
    double       f1 = f(m1), f2 = f(m2);
    while (hi - lo > step)
      if (f1 <= f2)
        {
          hi = m2, m2 = m1, f2 = f1;
          m1 = hi - golden * (hi - lo), f1 = f(m1);
        }
      else
        {
          lo = m1, m1 = m2, f1 = f2;
          m2 = lo + golden * (hi - lo), f2 = f(m2);
        }
    return std::min({f(lo), f(hi), f1, f2});
  }

  bool
  check_edge_contact_geometry(ConditionalOStream &pcout)
  {
    bool                                   passed = true;
    std::mt19937                           random(31);
    std::uniform_real_distribution<double> u(-1., 1.);
    for (const Obstacle &obstacle : shapes())
      {
        const ObstacleShape &shape = obstacle.shape();
        if (shape.core == ObstacleCore::half_space)
          continue;
        const physics::RigidPose pose = obstacle.pose(0.4);
        const std::string        name = obstacle.name();

        // Triangles with a corner outside and the others within 20 cm of it.
        double above = 0., below = 0., exact = 0.;
        for (unsigned int k = 0; k < 100; ++k)
          {
            std::array<Point<3>, 3> x;
            x[0] = outside(obstacle, pose, random);
            for (unsigned int i = 1; i < 3; ++i)
              x[i] = x[0] + 0.2 * Tensor<1, 3>({u(random), u(random), u(random)});
            const double       found   = obstacle.triangle_distance(pose, x, 1e-7);
            const unsigned int n       = 100; // (n + 1)(n + 2)/2 = 5,151 points
            double             sampled = std::numeric_limits<double>::infinity();
            for (unsigned int i = 0; i <= n; ++i)
              for (unsigned int j = 0; i + j <= n; ++j)
                sampled = std::min(sampled,
                                   obstacle
                                     .distance(pose,
                                               x[0] + (double(i) / n) * (x[1] - x[0]) +
                                                 (double(j) / n) * (x[2] - x[0]),
                                               false)
                                     .value);
            // d is 1-Lipschitz: the samples are within 0.2 √3 √2 / n of any point.
            above = std::max(above, found - sampled);
            below = std::max(below, sampled - found);
            // A sphere's and a capsule's are exact: against nested searches to 1e-10.
            if (shape.core == ObstacleCore::point || shape.core == ObstacleCore::segment)
              {
                const auto at = [&](const double a, const double b) {
                  return obstacle
                    .distance(pose, x[0] + a * (x[1] - x[0]) + b * (x[2] - x[0]), false)
                    .value;
                };
                const double searched = convex_min(
                  [&](const double a) {
                    return convex_min([&](const double b) { return at(a, b); },
                                      0.,
                                      1. - a,
                                      1e-10);
                  },
                  0.,
                  1.,
                  1e-10);
                exact = std::max(exact, std::abs(found - searched));
              }
          }
        if (shape.core == ObstacleCore::point || shape.core == ObstacleCore::segment)
          passed &= check_below(pcout,
                                name + ": triangle's distance against nested searches, m",
                                exact,
                                1e-9);
        passed &= check_below(pcout,
                              name + ": triangle's distance above its sampled minimum, m",
                              above,
                              1e-7);
        passed &= check_below(pcout,
                              name + ": triangle's distance below its sampled minimum, m",
                              below,
                              0.2 * std::sqrt(6.) / 100.);

        // The features less r against d, in the body frame.
        const std::shared_ptr<const physics::ObstacleSurface> features =
          physics::core_features(shape, 1e-5);
        double differs = 0., less = 0.;
        for (unsigned int k = 0; k < 2000; ++k)
          {
            const Point<3> y = pose.to_body(outside(obstacle, pose, random));
            double         f = std::numeric_limits<double>::infinity();
            for (const Point<3> &v : features->vertices)
              f = std::min(f, y.distance(v));
            for (const auto &e : features->edges)
              f = std::min(f,
                           segment_distance(y,
                                            features->vertices[e[0]],
                                            features->vertices[e[1]]));
            f -= shape.radius;
            const double d = physics::signed_distance(shape, y, false).value;
            less           = std::max(less, d - f);
            // Where the closest point of the core is on a feature.
            const Tensor<1, 3> w          = y - shape.center;
            bool               on_feature = true;
            if (shape.core == ObstacleCore::box)
              {
                unsigned int beyond = 0;
                for (unsigned int i = 0; i < 3; ++i)
                  beyond += std::abs(w[i]) > shape.half_extents[i] ? 1 : 0;
                on_feature = beyond >= 2;
              }
            if (shape.core == ObstacleCore::disc)
              on_feature = (w - (w * shape.axis) * shape.axis).norm() > shape.disc_radius;
            if (on_feature)
              differs = std::max(differs, std::abs(f - d));
          }
        const double tolerance = shape.core == ObstacleCore::disc ? 1e-5 : 1e-12;
        passed &= check_below(pcout,
                              name + ": d below the features' distance less r, m",
                              less,
                              tolerance);
        passed &= check_below(pcout,
                              name + ": the features' distance less r against d where "
                                     "they hold the closest point, m",
                              differs,
                              tolerance);
      }
    return passed;
  }

  bool
  check_core_steps(ConditionalOStream &pcout)
  {
    // The sphere of shapes() translates at 0.1 m/s and turns about its centre: its core
    // point moves 0.1 dt per step. A box (half extents 0.3, 0.1, 0.2) turning at 1 rad/s
    // about z through its centre, not translating: its corners, ρ = √0.1 m from the axis,
    // move by the chord 2 ρ sin(dt/2).
    const double  dt    = 0.1;
    ObstacleShape shape = shapes()[1].shape();
    shape.surface       = physics::core_features(shape, 1e-5);
    const Obstacle sphere(
      "sphere",
      shape,
      0.,
      [](const double t) {
        return Tensor<1, 3>({0.1 * t, -0.2, 0.3});
      },
      Tensor<1, 3>({0., 1., 1.}) / std::sqrt(2.),
      [](const double t) { return 0.7 + t; });
    shape         = shapes()[4].shape();
    shape.surface = physics::core_features(shape, 1e-5);
    const Obstacle box(
      "box",
      shape,
      0.,
      [](const double) { return Tensor<1, 3>(); },
      Tensor<1, 3>({0., 0., 1.}),
      [](const double t) { return t; });
    bool passed = check_near(pcout,
                             "sphere: largest core step / (0.1 m/s dt)",
                             largest_core_step(sphere, dt, 1.) / (0.1 * dt),
                             1.,
                             1e-12);
    // The same sphere jumping 100 m as it is removed at 0.5 s: its steps up to then.
    const Obstacle removed(
      "removed sphere",
      sphere.shape(),
      0.,
      [](const double t) {
        return Tensor<1, 3>({0.1 * t, -0.2, 0.3 - 100. * (t > 0.5)});
      },
      Tensor<1, 3>({0., 1., 1.}) / std::sqrt(2.),
      [](const double t) { return 0.7 + t; },
      0.5);
    passed &= check_near(pcout,
                         "sphere removed as it jumps: largest core step / (0.1 m/s dt)",
                         largest_core_step(removed, dt, 1.) / (0.1 * dt),
                         1.,
                         1e-12);
    passed &= check_near(pcout,
                         "turning box: largest core step / (2 ρ sin(ω dt / 2))",
                         largest_core_step(box, dt, 1.) /
                           (2. * std::sqrt(0.1) * std::sin(0.5 * dt)),
                         1.,
                         1e-12);

    TimeParameters time{};
    time.end_time          = 1.;
    time.time_step         = 0.25 * sphere.shape().radius / 0.1;
    time.maximum_time_step = 4. * time.time_step;
    ContactParameters contact{};
    contact.edge_contact_tangent = "automatic";
    for (const bool adaptive : {false, true})
      {
        time.adaptive_time_steps = adaptive;
        const std::string what   = adaptive ? "adaptive steps" : "fixed steps";
        passed &= check_near(pcout,
                             what + ": longest time step / the expected one",
                             longest_time_step(time) /
                               (adaptive ? time.maximum_time_step : time.time_step),
                             1.,
                             1e-15);
        const bool projected = projected_exact_pairs(contact, {sphere}, time)[0];
        passed &= check(pcout,
                        projected == adaptive,
                        what + ": 'automatic' takes the projected exact tangent: " +
                          (projected ? "yes" : "no"));
      }
    return passed;
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment                 env(argc, argv);
  ConditionalOStream         &pcout = env.pcout;
  const std::filesystem::path root  = scratch_directory("clothsim-contact-derivatives");
  pcout << "1. signed distances" << std::endl;
  bool passed = check_distances(pcout);
  pcout << "2. barrier and friction potentials" << std::endl;
  passed &= check_potentials(pcout);
  pcout << "3. the line search's cap" << std::endl;
  passed &= check_step_bounds(pcout);
  pcout << "4. contact and friction terms" << std::endl;
  passed &=
    check_terms(pcout,
                scratch_mesh(root / "mesh", {"swing-21.geo", "swing-grid.geo.inc"}));
  pcout << "5. edge contact's geometry" << std::endl;
  passed &= check_edge_contact_geometry(pcout);
  pcout << "6. how far a core moves in a step" << std::endl;
  passed &= check_core_steps(pcout);
  return finish(pcout, passed);
}
