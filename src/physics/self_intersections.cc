#include "physics/self_intersections.h"

#include "physics/aabb_tree.h"

#include <algorithm>
#include <cmath>

namespace clothsim::physics
{
  namespace
  {
    using Triangle = std::array<Point<3>, 3>;

    // Six times the signed volume of the tetrahedron p q r s.
    double
    orient3d(const Point<3> &p, const Point<3> &q, const Point<3> &r, const Point<3> &s)
    {
      return (q - p) * cross_product_3d(r - p, s - p);
    }

    // Points of a plane, projected along the axis where its normal is largest.
    struct Projection
    {
      unsigned int u, v;

      explicit Projection(const Tensor<1, 3> &normal)
      {
        unsigned int drop = 0;
        for (unsigned int d = 1; d < 3; ++d)
          if (std::abs(normal[d]) > std::abs(normal[drop]))
            drop = d;
        u = (drop + 1) % 3;
        v = (drop + 2) % 3;
      }

      // Twice the signed area of the projected triangle a b c.
      double
      orient(const Point<3> &a, const Point<3> &b, const Point<3> &c) const
      {
        return (b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]);
      }

      // p, collinear with a b, lies between them.
      bool
      within(const Point<3> &a, const Point<3> &b, const Point<3> &p) const
      {
        return std::min(a[u], b[u]) <= p[u] && p[u] <= std::max(a[u], b[u]) &&
               std::min(a[v], b[v]) <= p[v] && p[v] <= std::max(a[v], b[v]);
      }

      bool
      segments_meet(const Point<3> &a,
                    const Point<3> &b,
                    const Point<3> &c,
                    const Point<3> &d) const
      {
        const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
                     o4 = orient(c, d, b);
        if (((o1 > 0. && o2 < 0.) || (o1 < 0. && o2 > 0.)) &&
            ((o3 > 0. && o4 < 0.) || (o3 < 0. && o4 > 0.)))
          return true;
        return (o1 == 0. && within(a, b, c)) || (o2 == 0. && within(a, b, d)) ||
               (o3 == 0. && within(c, d, a)) || (o4 == 0. && within(c, d, b));
      }

      bool
      inside(const Point<3> &p, const Triangle &t) const
      {
        const double d0 = orient(t[0], t[1], p), d1 = orient(t[1], t[2], p),
                     d2 = orient(t[2], t[0], p);
        return (d0 >= 0. && d1 >= 0. && d2 >= 0.) || (d0 <= 0. && d1 <= 0. && d2 <= 0.);
      }
    };

    // Whether the segment a b meets the closed triangle t. A point within 1e-9 of the
    // pair's size (its longest edge) from the triangle's plane counts as in the plane.
    bool
    segment_meets_triangle(const Point<3> &a, const Point<3> &b, const Triangle &t)
    {
      const Tensor<1, 3> normal = cross_product_3d(t[1] - t[0], t[2] - t[0]);
      const double       area2  = normal.norm();
      if (area2 == 0.)
        return false; // a degenerate triangle: its edges are tested as segments
      double size = (b - a).norm();
      for (unsigned int i = 0; i < 3; ++i)
        size = std::max(size, (t[(i + 1) % 3] - t[i]).norm());
      const double tolerance = 1e-9 * size;
      const double ha = normal * (a - t[0]) / area2, hb = normal * (b - t[0]) / area2;
      if ((ha > tolerance && hb > tolerance) || (ha < -tolerance && hb < -tolerance))
        return false;
      if (std::abs(ha) <= tolerance && std::abs(hb) <= tolerance)
        {
          // The segment lies in the triangle's plane.
          const Projection plane(normal);
          if (plane.inside(a, t) || plane.inside(b, t))
            return true;
          for (unsigned int i = 0; i < 3; ++i)
            if (plane.segments_meet(a, b, t[i], t[(i + 1) % 3]))
              return true;
          return false;
        }
      // The segment crosses (or, within the tolerance, touches) the plane at one point:
      // inside the triangle when the line through a b passes on the same side of its
      // three edges.
      const double e0 = orient3d(a, b, t[0], t[1]), e1 = orient3d(a, b, t[1], t[2]),
                   e2 = orient3d(a, b, t[2], t[0]);
      return (e0 >= 0. && e1 >= 0. && e2 >= 0.) || (e0 <= 0. && e1 <= 0. && e2 <= 0.);
    }
  } // namespace


  bool
  triangles_intersect(const Triangle &a, const Triangle &b)
  {
    // Not coplanar: the triangles' common segment on the line where their planes meet
    // ends on an edge of one of them inside the other. Coplanar: an edge crosses, or a
    // corner of one lies inside the other (segment_meets_triangle's in-plane branch).
    for (unsigned int i = 0; i < 3; ++i)
      if (segment_meets_triangle(a[i], a[(i + 1) % 3], b) ||
          segment_meets_triangle(b[i], b[(i + 1) % 3], a))
        return true;
    return false;
  }


  std::vector<std::pair<unsigned int, unsigned int>>
  intersecting_pairs(const std::vector<MeshTriangle> &triangles)
  {
    std::vector<Box> boxes;
    boxes.reserve(triangles.size());
    for (const MeshTriangle &triangle : triangles)
      boxes.push_back(Box::around(triangle.corners));
    const AabbTree tree(boxes);

    std::vector<std::pair<unsigned int, unsigned int>> pairs;
    std::vector<unsigned int>                          candidates;
    for (unsigned int i = 0; i < triangles.size(); ++i)
      {
        candidates.clear();
        tree.find(boxes[i], candidates);
        for (const unsigned int j : candidates)
          {
            if (j <= i)
              continue;
            bool shared = false;
            for (const auto v : triangles[i].vertices)
              for (const auto w : triangles[j].vertices)
                shared = shared || v == w;
            if (!shared &&
                triangles_intersect(triangles[i].corners, triangles[j].corners))
              pairs.emplace_back(i, j);
          }
      }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
  }
} // namespace clothsim::physics
