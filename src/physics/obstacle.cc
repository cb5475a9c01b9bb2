#include "physics/obstacle.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>

#include "physics/pair_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace clothsim::physics
{
  namespace
  {
    Tensor<2, 3>
    identity()
    {
      Tensor<2, 3> I;
      for (unsigned int i = 0; i < 3; ++i)
        I[i][i] = 1.;
      return I;
    }

    // The distance to a point q with dq/dy = 0 (or rounded corners): ρ = |y - q|,
    // ∇ρ = n, ∇²ρ = (I - n nᵀ)/ρ restricted by `free` (dD/dy, a projector).
    SignedDistance
    distance_from(const Tensor<1, 3> &D,
                  const Tensor<2, 3> &free,
                  const double        radius,
                  const bool          derivatives)
    {
      SignedDistance d;
      const double   rho = D.norm();
      d.value            = rho - radius;
      if (derivatives && rho > 0.)
        {
          d.gradient = D / rho;
          d.hessian  = free * (identity() - outer_product(d.gradient, d.gradient)) * free;
          d.hessian /= rho;
        }
      return d;
    }

    // A function f(s, h) of the distance s from the axis a (through the origin) and the
    // height h along it, s = |w - (a·w) a| with e the unit radial direction:
    //   ∇f = f_s e + f_h a,
    //   ∇²f = f_ss e eᵀ + f_sh (e aᵀ + a eᵀ) + f_hh a aᵀ + f_s (I - a aᵀ - e eᵀ)/s.
    // Here f = sqrt((s - s0)² + h²) - r: the distance from the circle of radius s0 in
    // the plane h = 0, inflated by r, where s > 0.
    SignedDistance
    rim_distance(const Tensor<1, 3> &w,
                 const Tensor<1, 3> &a,
                 const double        s0,
                 const double        radius,
                 const bool          derivatives)
    {
      const double       h      = a * w;
      const Tensor<1, 3> radial = w - h * a;
      const double       s      = radial.norm();
      const double       ds = s - s0, dh = h;
      const double       rho = std::sqrt(ds * ds + dh * dh);
      SignedDistance     d;
      d.value = rho - radius;
      if (!derivatives || rho == 0.)
        return d;
      const Tensor<1, 3> e    = radial / s;
      const double       f_s  = ds / rho;
      const double       f_h  = dh / rho;
      const double       rho3 = rho * rho * rho;
      d.gradient              = f_s * e + f_h * a;
      d.hessian               = (dh * dh / rho3) * outer_product(e, e) -
                  (ds * dh / rho3) * (outer_product(e, a) + outer_product(a, e)) +
                  (ds * ds / rho3) * outer_product(a, a) +
                  (f_s / s) * (identity() - outer_product(a, a) - outer_product(e, e));
      return d;
    }

    // The minimum of a convex function f on [lo, hi] by golden-section search, to an
    // interval shorter than `tolerance` (at most 60 halvings of the golden ratio):
    // (where, value), `where` the lower end of the last interval.
    template <typename Function>
    std::pair<double, double>
    convex_minimum(const Function &f, double lo, double hi, const double tolerance)
    {
      const double golden = 0.5 * (std::sqrt(5.) - 1.);
      double       m1 = hi - golden * (hi - lo), m2 = lo + golden * (hi - lo);
      double       f1 = f(m1), f2 = f(m2);
      for (unsigned int i = 0; i < 60 && hi - lo > tolerance; ++i)
        if (f1 <= f2)
          {
            hi = m2;
            m2 = m1;
            f2 = f1;
            m1 = hi - golden * (hi - lo);
            f1 = f(m1);
          }
        else
          {
            lo = m1;
            m1 = m2;
            f1 = f2;
            m2 = lo + golden * (hi - lo);
            f2 = f(m2);
          }
      return {lo, std::min({f(lo), f1, f2})};
    }
  } // namespace


  SignedDistance
  signed_distance(const ObstacleShape &shape, const Point<3> &y, const bool derivatives)
  {
    const Tensor<1, 3> w = y - shape.center;
    const Tensor<1, 3> a = shape.axis;
    switch (shape.core)
      {
        case ObstacleCore::mesh:
          AssertThrow(false, ExcMessage("A mesh obstacle has no signed distance."));
          return {};
          case ObstacleCore::half_space: {
            SignedDistance d;
            d.value    = a * w;
            d.gradient = a;
            return d;
          }
        case ObstacleCore::point:
          return distance_from(w, identity(), shape.radius, derivatives);
          case ObstacleCore::segment: {
            // Beyond the ends: the distance from the end point.
            // Between the ends: the distance from the axis, D = (I - a aᵀ) w.
            const double h = a * w;
            if (std::abs(h) <= shape.half_length)
              return distance_from(w - h * a,
                                   identity() - outer_product(a, a),
                                   shape.radius,
                                   derivatives);
            const double end = h > 0. ? shape.half_length : -shape.half_length;
            return distance_from(w - end * a, identity(), shape.radius, derivatives);
          }
          case ObstacleCore::disc: {
            const double       h      = a * w;
            const Tensor<1, 3> radial = w - h * a;
            if (radial.norm() <= shape.disc_radius)
              {
                // Above or below the disc: the distance from its plane.
                SignedDistance d;
                d.value    = std::abs(h) - shape.radius;
                d.gradient = h >= 0. ? a : -a;
                return d;
              }
            return rim_distance(w, a, shape.disc_radius, shape.radius, derivatives);
          }
          case ObstacleCore::box: {
            // q = clamp(w, -b, b); D = w - q varies with the clamped components only.
            Tensor<1, 3> D;
            Tensor<2, 3> free;
            bool         inside = true;
            double       depth  = std::numeric_limits<double>::infinity();
            for (unsigned int i = 0; i < 3; ++i)
              {
                const double b = shape.half_extents[i];
                if (std::abs(w[i]) > b)
                  {
                    D[i]       = w[i] - (w[i] > 0. ? b : -b);
                    free[i][i] = 1.;
                    inside     = false;
                  }
                depth = std::min(depth, b - std::abs(w[i]));
              }
            if (!inside)
              return distance_from(D, free, shape.radius, derivatives);
            // Inside the core (deep penetration): a negative value suffices.
            SignedDistance d;
            d.value = -depth - shape.radius;
            return d;
          }
      }
    Assert(false, ExcNotImplemented());
    return {};
  }


  std::shared_ptr<const ObstacleSurface>
  core_features(const ObstacleShape &shape, const double tolerance)
  {
    std::vector<Point<3>>                    vertices;
    std::vector<std::array<unsigned int, 2>> edges;
    const Point<3>                          &c = shape.center;
    switch (shape.core)
      {
        case ObstacleCore::half_space:
        case ObstacleCore::mesh:
          return nullptr;
        case ObstacleCore::point:
          vertices = {c};
          break;
        case ObstacleCore::segment:
          vertices = {c - shape.half_length * shape.axis,
                      c + shape.half_length * shape.axis};
          edges    = {{{0, 1}}};
          break;
          case ObstacleCore::box: {
            // Corner k has the sign of bit i of k along body axis i.
            for (unsigned int k = 0; k < 8; ++k)
              {
                Point<3> corner = c;
                for (unsigned int i = 0; i < 3; ++i)
                  corner[i] += ((k >> i) & 1 ? 1. : -1.) * shape.half_extents[i];
                vertices.push_back(corner);
              }
            for (unsigned int k = 0; k < 8; ++k)
              for (unsigned int i = 0; i < 3; ++i)
                if (((k >> i) & 1) == 0)
                  edges.push_back({{k, k | (1u << i)}});
            break;
          }
          case ObstacleCore::disc: {
            // M sides circumscribing the circle: they touch it at their midpoints and
            // their corners lie R (1/cos(π/M) - 1) outside it. The polygon holds the
            // circle, so no point is farther from it than from the circle: what the
            // pairs keep off the polygon is off the rim.
            const double R = shape.disc_radius;
            const auto   n = static_cast<unsigned int>(
              std::ceil(numbers::PI / std::acos(R / (R + tolerance))));
            const unsigned int M      = std::max(n, 3u);
            const double       corner = R / std::cos(numbers::PI / M);
            Tensor<1, 3>       e[2];
            Tensor<1, 3>       helper;
            helper[std::abs(shape.axis[0]) < 0.9 ? 0 : 1] = 1.;
            e[0] = helper - (helper * shape.axis) * shape.axis;
            e[0] /= e[0].norm();
            e[1] = cross_product_3d(shape.axis, e[0]);
            for (unsigned int k = 0; k < M; ++k)
              {
                const double phi = 2. * numbers::PI * k / M;
                vertices.push_back(c + corner *
                                         (std::cos(phi) * e[0] + std::sin(phi) * e[1]));
                edges.push_back({{k, (k + 1) % M}});
              }
            break;
          }
      }
    return std::make_shared<const ObstacleSurface>(
      std::move(vertices), std::vector<std::array<unsigned int, 3>>(), std::move(edges));
  }


  Obstacle::Obstacle(const std::string                        &name,
                     const ObstacleShape                      &shape,
                     const double                              friction,
                     std::function<Tensor<1, 3>(const double)> translation,
                     const Tensor<1, 3>                       &rotation_axis,
                     std::function<double(const double)>       angle,
                     const double                              removal_time)
    : obstacle_name(name)
    , body_shape(shape)
    , friction_coefficient(friction)
    , translation(std::move(translation))
    , rotation_axis(rotation_axis / rotation_axis.norm())
    , angle(std::move(angle))
    , removal_time(removal_time)
  {}


  RigidPose
  Obstacle::pose(const double t) const
  {
    // Rodrigues: R = cos θ I + sin θ [k]x + (1 - cos θ) k kᵀ.
    const double        theta = angle(t);
    const Tensor<1, 3> &k     = rotation_axis;
    const double        c = std::cos(theta), s = std::sin(theta);
    RigidPose           pose;
    pose.rotation = c * identity() + (1. - c) * outer_product(k, k);
    pose.rotation[0][1] -= s * k[2];
    pose.rotation[0][2] += s * k[1];
    pose.rotation[1][0] += s * k[2];
    pose.rotation[1][2] -= s * k[0];
    pose.rotation[2][0] -= s * k[1];
    pose.rotation[2][1] += s * k[0];
    // x = R (y - c) + c + T.
    const Tensor<1, 3> center = body_shape.center;
    pose.translation          = center + translation(t) - pose.rotation * center;
    pose.present              = t <= removal_time;
    return pose;
  }


  SignedDistance
  Obstacle::distance(const RigidPose &pose,
                     const Point<3>  &x,
                     const bool       derivatives) const
  {
    if (!pose.present)
      return {std::numeric_limits<double>::infinity(), Tensor<1, 3>(), Tensor<2, 3>()};
    SignedDistance d = signed_distance(body_shape, pose.to_body(x), derivatives);
    if (derivatives)
      {
        const Tensor<2, 3> &R = pose.rotation;
        d.gradient            = R * d.gradient;
        d.hessian             = R * d.hessian * transpose(R);
      }
    return d;
  }


  double
  Obstacle::step_bound(const RigidPose    &pose,
                       const Point<3>     &x,
                       const Tensor<1, 3> &dx,
                       const double        fraction) const
  {
    if (!pose.present)
      return 1.;
    const Point<3>     y     = pose.to_body(x);
    const Tensor<1, 3> dy    = transpose(pose.rotation) * dx;
    const double       d0    = signed_distance(body_shape, y, false).value;
    const double       level = fraction * d0;
    // d is 1-Lipschitz: a path shorter than d0 - level cannot reach the level.
    if (dy.norm() <= d0 - level)
      return 1.;
    const auto d = [&](const double s) {
      return signed_distance(body_shape, Point<3>(y + s * dy), false).value;
    };
    if (body_shape.core == ObstacleCore::half_space)
      {
        const double rate = body_shape.axis * dy;
        return rate >= 0. ? 1. : std::min(1., (d0 - level) / -rate);
      }
    // d(s) is convex: its minimum on [0, 1].
    const double s_min = convex_minimum(d, 0., 1., 1e-12).first;
    if (d(s_min) > level && d(1.) > level)
      return 1.;
    // The first crossing lies in [0, s_min] (or [0, 1]), where d decreases: bisect.
    double above = 0., below = d(s_min) <= level ? s_min : 1.;
    for (unsigned int i = 0; i < 60; ++i)
      {
        const double middle                 = 0.5 * (above + below);
        (d(middle) > level ? above : below) = middle;
      }
    return above;
  }


  double
  Obstacle::triangle_distance(const RigidPose               &pose,
                              const std::array<Point<3>, 3> &x,
                              const double                   tolerance) const
  {
    if (!pose.present)
      return std::numeric_limits<double>::infinity();
    const Point<3>     y0 = pose.to_body(x[0]);
    const Tensor<1, 3> e1 = pose.to_body(x[1]) - y0, e2 = pose.to_body(x[2]) - y0;
    const auto         d = [&](const double a, const double b) {
      return signed_distance(body_shape, Point<3>(y0 + a * e1 + b * e2), false).value;
    };
    // Affine along the triangle: its minimum is at a corner.
    if (body_shape.core == ObstacleCore::half_space)
      return std::min({d(0., 0.), d(1., 0.), d(0., 1.)});
    const Point<3> y1(y0 + e1), y2(y0 + e2);
    // A ball: its centre's distance from the triangle, less the radius.
    if (body_shape.core == ObstacleCore::point)
      return std::sqrt(pair_squared_distance(PairKind::point_triangle,
                                             {{body_shape.center, y0, y1, y2}})) -
             body_shape.radius;
    // A capsule: its segment's distance from the triangle (zero where it passes
    // through; else attained at an end of the segment or on an edge of the triangle).
    if (body_shape.core == ObstacleCore::segment)
      {
        const Point<3> a(body_shape.center - body_shape.half_length * body_shape.axis);
        const Point<3> b(body_shape.center + body_shape.half_length * body_shape.axis);
        if (segment_crosses_triangle(a, b, y0, y1, y2))
          return -body_shape.radius;
        double squared =
          std::min(pair_squared_distance(PairKind::point_triangle, {{a, y0, y1, y2}}),
                   pair_squared_distance(PairKind::point_triangle, {{b, y0, y1, y2}}));
        for (const auto &[p, q] :
             {std::pair(y0, y1), std::pair(y1, y2), std::pair(y2, y0)})
          squared =
            std::min(squared, pair_squared_distance(PairKind::edge_edge, {{a, b, p, q}}));
        return std::sqrt(squared) - body_shape.radius;
      }
    // f(a, b) = d(y0 + a e1 + b e2) over a, b >= 0, a + b <= 1; an interval of length
    // τ/|e| in a barycentric coordinate moves the point by less than τ.
    const double longest = std::max({e1.norm(), e2.norm(), (e2 - e1).norm()});
    const double step    = tolerance / std::max(longest, tolerance);
    const auto   over_b  = [&](const double a) {
      return convex_minimum([&](const double b) { return d(a, b); }, 0., 1. - a, step)
        .second;
    };
    return convex_minimum(over_b, 0., 1., step).second;
  }
} // namespace clothsim::physics
