#pragma once

// Distances between the primitives of triangle surfaces, for contact of the cloth with
// triangle-mesh obstacles (and of the cloth with itself): a point and a triangle, two
// edges. A pair is four points,
//   point-triangle: p, t0, t1, t2;      edge-edge: a0, a1, b0, b1,
// and its squared distance is one of four smooth forms, chosen by where the closest
// points lie (the distance type of Li et al., "Incremental Potential Contact", 2020,
// sec. 4.1):
//   point-point   |p - q|²
//   point-line    |(a - p) × (b - p)|² / |b - a|²
//   point-plane   ((p - a)·n)² / |n|²,          n = (b - a) × (c - a)
//   line-line     ((b0 - a0)·n)² / |n|²,        n = (a1 - a0) × (b1 - b0)
// Each form is the true squared distance where its type holds, so the pair's distance is
// continuous, and smooth within each type.

#include <deal.II/base/point.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace clothsim::physics
{
  using namespace dealii;

  enum class PairKind
  {
    point_triangle,
    edge_edge
  };

  using PairPoints = std::array<Point<3>, 4>;

  // One of the four forms and the pair's points it reads (indices into PairPoints).
  struct DistanceType
  {
    enum Form
    {
      point_point,
      point_line,
      point_plane,
      line_line
    } form;
    std::array<unsigned int, 4> points; // the first 2, 3, 4, 4 are used
  };

  // The type that holds at `x`. Nearly parallel edges (sin² of their angle below 1e-12)
  // are measured from their end points (line-line is ill-conditioned there).
  DistanceType
  distance_type(const PairKind kind, const PairPoints &x);

  // The squared distance (m²) of `type`'s form at x.
  double
  squared_distance(const DistanceType &type, const PairPoints &x);

  // Weights w with r = Σ w_i x_i the vector from the second primitive's closest point
  // to the first's (|r|² the squared distance): the first primitive's weights are its
  // closest point's barycentric coordinates, the second's their negatives.
  std::array<double, 4>
  closest_point_weights(const DistanceType &type, const PairPoints &x);

  // Whether the segment a b passes through the triangle t0 t1 t2 (touching counts): the
  // ends on both sides of the triangle's plane, and the line through them on the same
  // side of each of its edges (signs of volumes).
  bool
  segment_crosses_triangle(const Point<3> &a,
                           const Point<3> &b,
                           const Point<3> &t0,
                           const Point<3> &t1,
                           const Point<3> &t2);

  // Both at once: the squared distance between the primitives.
  inline double
  pair_squared_distance(const PairKind kind, const PairPoints &x)
  {
    return squared_distance(distance_type(kind, x), x);
  }

  namespace pair_detail
  {
    template <typename Number>
    using Vec = std::array<Number, 3>;

    template <typename Number>
    Vec<Number>
    minus(const Vec<Number> &a, const Vec<Number> &b)
    {
      return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}};
    }

    template <typename Number>
    Number
    dot(const Vec<Number> &a, const Vec<Number> &b)
    {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    }

    template <typename Number>
    Vec<Number>
    cross(const Vec<Number> &a, const Vec<Number> &b)
    {
      return {{a[1] * b[2] - a[2] * b[1],
               a[2] * b[0] - a[0] * b[2],
               a[0] * b[1] - a[1] * b[0]}};
    }
  } // namespace pair_detail

  // A form evaluated on any number type (Sacado's for derivatives): `x` holds the
  // four points' coordinates.
  template <typename Number>
  Number
  squared_distance(const DistanceType::Form                    form,
                   const std::array<std::array<Number, 3>, 4> &x,
                   const std::array<unsigned int, 4>          &points)
  {
    using Vec = pair_detail::Vec<Number>;
    using pair_detail::cross;
    using pair_detail::dot;
    using pair_detail::minus;
    const Vec &p = x[points[0]], &a = x[points[1]];
    switch (form)
      {
          case DistanceType::point_point: {
            const Vec d = minus(p, a);
            return dot(d, d);
          }
          case DistanceType::point_line: {
            const Vec &b = x[points[2]];
            const Vec  e = minus(b, a);
            const Vec  n = cross(minus(a, p), minus(b, p));
            return dot(n, n) / dot(e, e);
          }
          case DistanceType::point_plane: {
            const Vec   &b = x[points[2]], &c = x[points[3]];
            const Vec    n      = cross(minus(b, a), minus(c, a));
            const Number height = dot(minus(p, a), n);
            return height * height / dot(n, n);
          }
        case DistanceType::line_line:
          default: {
            // points: a0 = p, a1 = a, b0, b1.
            const Vec   &b0 = x[points[2]], &b1 = x[points[3]];
            const Vec    n      = cross(minus(a, p), minus(b1, b0));
            const Number height = dot(minus(b0, p), n);
            return height * height / dot(n, n);
          }
      }
  }


  // The centre of the box around the motions m(p) of the points p < n: their common
  // part (distances do not change when every point moves by the same vector).
  template <typename Motion>
  Tensor<1, 3>
  common_motion(const unsigned int n, const Motion &motion)
  {
    Tensor<1, 3> low, high;
    for (unsigned int d = 0; d < 3; ++d)
      {
        low[d]  = std::numeric_limits<double>::infinity();
        high[d] = -std::numeric_limits<double>::infinity();
      }
    for (unsigned int p = 0; p < n; ++p)
      {
        const Tensor<1, 3> m = motion(p);
        for (unsigned int d = 0; d < 3; ++d)
          {
            low[d]  = std::min(low[d], m[d]);
            high[d] = std::max(high[d], m[d]);
          }
      }
    return (low + high) / 2.;
  }


  // The largest |m(p) - c| over points p < n, c their common motion (above). It bounds
  // how far the motions can change the distance of any pair (by at most twice it): a
  // falling sheet's translation moves none.
  template <typename Motion>
  double
  largest_relative_motion(const unsigned int n, const Motion &motion)
  {
    const Tensor<1, 3> centre  = common_motion(n, motion);
    double             largest = 0.;
    for (unsigned int p = 0; p < n; ++p)
      largest = std::max(largest, (motion(p) - centre).norm_square());
    return std::sqrt(largest);
  }


  // A bound L on how fast the pair's distance changes along the straight path x + s dx:
  // |d(s) - d(0)| <= L s. L is the largest motion of a point of one primitive plus that
  // of the other, after the four points' mean motion (which moves no distance) is taken
  // out.
  double
  pair_motion_bound(const PairKind kind, const PairPoints &dx);

  // The largest α in [0, 1] such that the pair's distance stays at or above `fraction`
  // of its start value d0 on the straight path x + s dx, s in [0, α] (continuous
  // collision detection, after the additive CCD of Li, Kaufman and Jiang, "Codimensional
  // Incremental Potential Contact", 2021): the distance moves at most L per unit of s,
  // L the largest motion of a point of one primitive plus that of the other, so
  // advancing by (d - fraction d0) / L cannot cross; the advance repeats until d is
  // within a quarter of fraction d0 above it, s reaches 1, or after 100 advances.
  // Conservative. `x` must have a positive distance. With an `offset` r (m) the distance
  // is the pair's less r (an obstacle's core inflated by r).
  double
  pair_step_bound(const PairKind    kind,
                  const PairPoints &x,
                  const PairPoints &dx,
                  const double      fraction,
                  const double      offset = 0.);

  // A lower bound on the distance of every pair of the hinge of two triangles (a, b, p)
  // and (a, b, q) (shared edge ab, opposite vertices p and q: each opposite vertex
  // against the other triangle, and the edges pa, pb against bq, aq) at these
  // positions, if it is open by 90 degrees or more; 0 where it is folded further. Then
  // each point of one triangle is at least its distance from the edge's line away from
  // the other's half-plane.
  double
  hinge_distance_bound(const Point<3> &a,
                       const Point<3> &b,
                       const Point<3> &p,
                       const Point<3> &q);
} // namespace clothsim::physics
