#include "physics/pair_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace clothsim::physics
{
  namespace
  {
    std::array<std::array<double, 3>, 4>
    coordinates(const PairPoints &x)
    {
      std::array<std::array<double, 3>, 4> c;
      for (unsigned int i = 0; i < 4; ++i)
        for (unsigned int d = 0; d < 3; ++d)
          c[i][d] = x[i][d];
      return c;
    }

    // The closest point of segment a b to p: its squared distance |p - a - t (b - a)|²,
    // t clamped to [0, 1] (no branches: four of these per edge-edge pair), and t.
    struct SegmentPoint
    {
      double       squared_distance, t;
      unsigned int p, a, b;
    };
    SegmentPoint
    closest_on_segment(const PairPoints  &x,
                       const unsigned int p,
                       const unsigned int a,
                       const unsigned int b)
    {
      // In plain doubles: this runs tens of millions of times in a self-contact run,
      // and GCC keeps deal.II's Point::operator- out of line.
      double e[3], v[3], ee = 0., ve = 0.;
      for (unsigned int d = 0; d < 3; ++d)
        {
          e[d] = x[b][d] - x[a][d];
          v[d] = x[p][d] - x[a][d];
          ee += e[d] * e[d];
          ve += v[d] * e[d];
        }
      const double t  = std::clamp(ve / ee, 0., 1.);
      double       d2 = 0.;
      for (unsigned int d = 0; d < 3; ++d)
        d2 += (v[d] - t * e[d]) * (v[d] - t * e[d]);
      return {d2, t, p, a, b};
    }

    // The type of the candidate closest to its point: point-point at a segment's end,
    // else point-line.
    template <std::size_t n>
    DistanceType
    closest_of(const std::array<SegmentPoint, n> &candidates)
    {
      const SegmentPoint *best = &candidates[0];
      for (const SegmentPoint &candidate : candidates)
        if (candidate.squared_distance < best->squared_distance)
          best = &candidate;
      if (best->t <= 0.)
        return {DistanceType::point_point, {{best->p, best->a, 0, 0}}};
      if (best->t >= 1.)
        return {DistanceType::point_point, {{best->p, best->b, 0, 0}}};
      return {DistanceType::point_line, {{best->p, best->a, best->b, 0}}};
    }
  } // namespace


  double
  squared_distance(const DistanceType &type, const PairPoints &x)
  {
    return squared_distance<double>(type.form, coordinates(x), type.points);
  }


  std::array<double, 4>
  closest_point_weights(const DistanceType &type, const PairPoints &x)
  {
    // The parameter of the point of line a b closest to p.
    const auto along =
      [&x](const unsigned int p, const unsigned int a, const unsigned int b) {
        const Tensor<1, 3> e = x[b] - x[a];
        return (x[p] - x[a]) * e / e.norm_square();
      };
    std::array<double, 4>              w{};
    const std::array<unsigned int, 4> &i = type.points;
    switch (type.form)
      {
        case DistanceType::point_point:
          w[i[0]] = 1.;
          w[i[1]] = -1.;
          break;
          case DistanceType::point_line: {
            const double t = along(i[0], i[1], i[2]);
            w[i[0]]        = 1.;
            w[i[1]]        = -(1. - t);
            w[i[2]]        = -t;
            break;
          }
          case DistanceType::point_plane: {
            const Tensor<1, 3> e0 = x[i[2]] - x[i[1]], e1 = x[i[3]] - x[i[1]];
            const Tensor<1, 3> n = cross_product_3d(e0, e1), v = x[i[0]] - x[i[1]];
            const double       b1 = cross_product_3d(v, e1) * n / n.norm_square();
            const double       b2 = cross_product_3d(e0, v) * n / n.norm_square();
            w[i[0]]               = 1.;
            w[i[1]]               = -(1. - b1 - b2);
            w[i[2]]               = -b1;
            w[i[3]]               = -b2;
            break;
          }
          case DistanceType::line_line: {
            const Tensor<1, 3> ea = x[i[1]] - x[i[0]], eb = x[i[3]] - x[i[2]];
            const Tensor<1, 3> v = x[i[0]] - x[i[2]];
            const double A = ea * ea, B = ea * eb, C = eb * eb, D = ea * v, E = eb * v;
            const double det = A * C - B * B;
            const double s = (B * E - C * D) / det, t = (A * E - B * D) / det;
            w[i[0]] = 1. - s;
            w[i[1]] = s;
            w[i[2]] = -(1. - t);
            w[i[3]] = -t;
            break;
          }
      }
    // The point-point and point-line forms of an edge-edge pair may have the second
    // edge's end first: make the first edge's weights the positive ones.
    if (w[0] + w[1] < 0.)
      for (double &wi : w)
        wi = -wi;
    return w;
  }


  DistanceType
  distance_type(const PairKind kind, const PairPoints &x)
  {
    if (kind == PairKind::point_triangle)
      {
        // Inside the triangle's prism the plane is closest; else its boundary.
        const Tensor<1, 3> e0 = x[2] - x[1], e1 = x[3] - x[1];
        const Tensor<1, 3> n  = cross_product_3d(e0, e1);
        const Tensor<1, 3> w  = x[0] - x[1];
        const double       nn = n.norm_square();
        // Barycentric coordinates of p's projection: (1 - b1 - b2, b1, b2).
        const double b1 = cross_product_3d(w, e1) * n / nn;
        const double b2 = cross_product_3d(e0, w) * n / nn;
        if (b1 > 0. && b2 > 0. && b1 + b2 < 1.)
          return {DistanceType::point_plane, {{0, 1, 2, 3}}};
        return closest_of(std::array<SegmentPoint, 3>{{closest_on_segment(x, 0, 1, 2),
                                                       closest_on_segment(x, 0, 2, 3),
                                                       closest_on_segment(x, 0, 3, 1)}});
      }

    // Edges: the minimum of |a0 + s ea - b0 - t eb|² over the unit square is inside it
    // (line-line) or on one of its sides (an end point against the other segment).
    const Tensor<1, 3> ea = x[1] - x[0], eb = x[3] - x[2], w = x[0] - x[2];
    const double       A = ea * ea, B = ea * eb, C = eb * eb, D = ea * w, E = eb * w;
    const double       det = A * C - B * B; // |ea × eb|²
    if (det > 1e-12 * A * C)
      {
        const double s = (B * E - C * D) / det, t = (A * E - B * D) / det;
        if (s > 0. && s < 1. && t > 0. && t < 1.)
          return {DistanceType::line_line, {{0, 1, 2, 3}}};
      }
    return closest_of(std::array<SegmentPoint, 4>{{closest_on_segment(x, 0, 2, 3),
                                                   closest_on_segment(x, 1, 2, 3),
                                                   closest_on_segment(x, 2, 0, 1),
                                                   closest_on_segment(x, 3, 0, 1)}});
  }


  bool
  segment_crosses_triangle(const Point<3> &a,
                           const Point<3> &b,
                           const Point<3> &t0,
                           const Point<3> &t1,
                           const Point<3> &t2)
  {
    // Six times the signed volume of the tetrahedron p q r s.
    const auto volume =
      [](const Point<3> &p, const Point<3> &q, const Point<3> &r, const Point<3> &s) {
        return (q - p) * cross_product_3d(r - p, s - p);
      };
    const double va = volume(a, t0, t1, t2), vb = volume(b, t0, t1, t2);
    if ((va > 0. && vb > 0.) || (va < 0. && vb < 0.))
      return false;
    const double e0 = volume(a, b, t0, t1), e1 = volume(a, b, t1, t2),
                 e2 = volume(a, b, t2, t0);
    return (e0 >= 0. && e1 >= 0. && e2 >= 0.) || (e0 <= 0. && e1 <= 0. && e2 <= 0.);
  }


  double
  pair_motion_bound(const PairKind kind, const PairPoints &dx)
  {
    // The largest motion of a point of the first primitive plus that of the second,
    // after their common mean motion (which moves no distance) is taken out.
    Tensor<1, 3> mean;
    for (const Point<3> &d : dx)
      mean += d;
    mean /= 4.;
    const unsigned int first = kind == PairKind::point_triangle ? 1 : 2;
    double             L0 = 0., L1 = 0.;
    for (unsigned int i = 0; i < 4; ++i)
      (i < first ? L0 : L1) = std::max(i < first ? L0 : L1, (dx[i] - mean).norm());
    return L0 + L1;
  }


  double
  pair_step_bound(const PairKind    kind,
                  const PairPoints &x,
                  const PairPoints &dx,
                  const double      fraction,
                  const double      offset)
  {
    const double L = pair_motion_bound(kind, dx);

    const double d0  = std::sqrt(pair_squared_distance(kind, x)) - offset;
    const double gap = fraction * d0;
    if (L <= d0 - gap)
      return 1.;
    // Each advance keeps d >= gap on the way; stop once d is within a quarter of the
    // gap above it (the rest would take many small advances) or after 100.
    double     s = 0., d = d0;
    PairPoints y;
    for (unsigned int k = 0; k < 100; ++k)
      {
        const double next = s + (d - gap) / L;
        if (next >= 1.)
          return 1.;
        for (unsigned int i = 0; i < 4; ++i)
          y[i] = x[i] + next * dx[i];
        d = std::sqrt(pair_squared_distance(kind, y)) - offset;
        s = next;
        if (d < 1.25 * gap)
          break;
      }
    return s;
  }


  double
  hinge_distance_bound(const Point<3> &a,
                       const Point<3> &b,
                       const Point<3> &p,
                       const Point<3> &q)
  {
    // In the edge's frame: s along it from a (length L), r_p and r_q the opposite
    // vertices' offsets from its line (heights h_p, h_q). Open by 90 degrees or more
    // (r_p · r_q <= 0), a point at (s, t) on one side and one at (s', t') on the other
    // are at least √((s - s')² + t² + t'²) apart. So a vertex is at least its height
    // from the other triangle, and an edge from a (toward p) from one from b (toward q)
    // at least L / (1 + |s_p| / h_p + |s_q - L| / h_q): where both points are within τ
    // of the line, they lie within τ |s_p| / h_p of a and τ |s_q - L| / h_q of b.
    // With E = b - a, P = p - a, Q = q - a: L² r_p · r_q = (P · Q) L² - (P · E)(Q · E),
    // L h_p = |P x E|, L s_p = P · E.
    const Tensor<1, 3> E = b - a, P = p - a, Q = q - a;
    const double       ee = E * E, pe = P * E, qe = Q * E;
    if ((P * Q) * ee - pe * qe > 0.)
      return 0.;
    const double cross_p = cross_product_3d(P, E).norm(),
                 cross_q = cross_product_3d(Q, E).norm();
    if (cross_p == 0. || cross_q == 0.)
      return 0.;
    const double length = std::sqrt(ee);
    return std::min(
      {cross_p / length,
       cross_q / length,
       length / (1. + std::abs(pe) / cross_p + std::abs(qe - ee) / cross_q),
       length / (1. + std::abs(qe) / cross_q + std::abs(pe - ee) / cross_p)});
  }
} // namespace clothsim::physics
