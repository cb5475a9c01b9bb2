// The self-intersection checker (physics/self_intersections.h) against configurations
// whose answer is known by construction, and its BVH pass against all pairs.
//  1. Pairs of triangles: crossing (a pierces b), disjoint, a corner of one touching the
//     other's face, coplanar and overlapping, coplanar and apart, coplanar with one
//     inside the other, an edge lying in the other's plane but outside it (the
//     false positive a plain orientation test gives), parallel planes 1e-6 apart.
//  2. A flat 21 x 21-vertex grid has no intersecting pair (its triangles are coplanar
//     and touch only their neighbours, which share vertices); folded by 170° about its
//     middle line (the upper half 8.7 cm above the lower at its far edge) still none;
//     folded by 180° with the upper half tilted so that it passes through the lower
//     half along y = 1/4, many, and every one a pair of one triangle from each half.
//  3. Random soups of 300 small triangles: the pairs found through the BVH are exactly
//     those found by testing every pair.

#include "physics/self_intersections.h"
#include "test_checks.h"

#include <random>
#include <set>

using namespace clothsim::physics;
using namespace clothsim::test;

namespace
{
  using Triangle = std::array<Point<3>, 3>;

  Triangle
  moved(const Triangle &t, const Tensor<1, 3> &shift)
  {
    return {{t[0] + shift, t[1] + shift, t[2] + shift}};
  }

  // The structured grid of n x n vertices on [0, 1]², alternating diagonals; vertex
  // (i, j) at x = i/(n-1), y = j/(n-1), mapped by `place`.
  template <typename Place>
  std::vector<MeshTriangle>
  grid(const unsigned int n, const Place &place)
  {
    std::vector<MeshTriangle> triangles;
    const auto id = [n](unsigned int i, unsigned int j) { return j * n + i; };
    const auto at = [&](unsigned int i, unsigned int j) {
      return place(i / double(n - 1), j / double(n - 1));
    };
    for (unsigned int j = 0; j + 1 < n; ++j)
      for (unsigned int i = 0; i + 1 < n; ++i)
        {
          const bool                                       flip = (i + j) % 2 == 1;
          const std::array<std::array<unsigned int, 2>, 6> corners =
            flip ? std::array<std::array<unsigned int, 2>, 6>{{{{i, j}},
                                                               {{i + 1, j}},
                                                               {{i, j + 1}},
                                                               {{i + 1, j}},
                                                               {{i + 1, j + 1}},
                                                               {{i, j + 1}}}}
                 : std::array<std::array<unsigned int, 2>, 6>{{{{i, j}},
                                                               {{i + 1, j}},
                                                               {{i + 1, j + 1}},
                                                               {{i, j}},
                                                               {{i + 1, j + 1}},
                                                               {{i, j + 1}}}};
          for (unsigned int t = 0; t < 2; ++t)
            {
              MeshTriangle triangle;
              for (unsigned int v = 0; v < 3; ++v)
                {
                  const auto [a, b]    = corners[3 * t + v];
                  triangle.corners[v]  = at(a, b);
                  triangle.vertices[v] = id(a, b);
                }
              triangles.push_back(triangle);
            }
        }
    return triangles;
  }

  // The grid folded about the line y = 1/2, z = 0 by `angle` (rad; π: flat onto the
  // lower half): the upper half's point at distance r from the line goes to
  // (x, 1/2 + r cos(angle), r sin(angle) + tilt (r - 1/4)). With angle = π and tilt > 0
  // it passes below the lower half near the fold and above it beyond r = 1/4.
  std::vector<MeshTriangle>
  folded(const unsigned int n, const double angle, const double tilt)
  {
    return grid(n, [&](const double x, const double y) {
      if (y <= 0.5)
        return Point<3>(x, y, 0.);
      const double r = y - 0.5;
      return Point<3>(x,
                      0.5 + r * std::cos(angle),
                      r * std::sin(angle) + tilt * (r - 0.25));
    });
  }
} // namespace


int
main()
{
  ConditionalOStream out(std::cout, true);
  const Triangle     base = {
        {Point<3>(0., 0., 0.), Point<3>(1., 0., 0.), Point<3>(0., 1., 0.)}};

  out << "1. pairs of triangles" << std::endl;
  {
    const Triangle piercing = {
      {Point<3>(0.2, 0.2, -0.5), Point<3>(0.3, 0.2, 0.5), Point<3>(0.25, 0.9, 0.5)}};
    check(out, triangles_intersect(base, piercing), "a triangle piercing another");
    check(out, triangles_intersect(piercing, base), "... in the other order");
    check(out,
          !triangles_intersect(base, moved(piercing, Tensor<1, 3>({2., 0., 0.}))),
          "disjoint (moved 2 m along x)");
    const Triangle touching = {
      {Point<3>(0.2, 0.2, 0.), Point<3>(0.3, 0.2, 0.5), Point<3>(0.25, 0.4, 0.5)}};
    check(out, triangles_intersect(base, touching), "a corner touching the face");
    check(out,
          !triangles_intersect(base, moved(touching, Tensor<1, 3>({0., 0., 1e-6}))),
          "the same corner 1e-6 m above the face");
    check(out,
          triangles_intersect(base, moved(base, Tensor<1, 3>({0.3, 0.3, 0.}))),
          "coplanar, overlapping");
    check(out,
          !triangles_intersect(base, moved(base, Tensor<1, 3>({1.5, 0., 0.}))),
          "coplanar, apart");
    const Triangle inner = {
      {Point<3>(0.1, 0.1, 0.), Point<3>(0.2, 0.1, 0.), Point<3>(0.1, 0.2, 0.)}};
    check(out, triangles_intersect(base, inner), "coplanar, one inside the other");
    // An edge in the base's plane (z = 0) but 1 m away from it, the triangle rising off
    // the plane: orientation signs of that edge against the base are all zero.
    const Triangle in_plane_edge = {
      {Point<3>(2., 0., 0.), Point<3>(2., 1., 0.), Point<3>(2.5, 0.5, 0.7)}};
    check(out,
          !triangles_intersect(base, in_plane_edge),
          "an edge in the plane, 1 m away");
    check(out,
          !triangles_intersect(base, moved(base, Tensor<1, 3>({0., 0., 1e-6}))),
          "parallel planes 1e-6 m apart");
  }

  out << "2. a grid of 21 x 21 vertices, flat and folded" << std::endl;
  {
    const unsigned int n = 21;
    check_equal<std::size_t>(out,
                             "flat: intersecting pairs",
                             intersecting_pairs(folded(n, 0., 0.)).size(),
                             0);
    check_equal<std::size_t>(
      out,
      "folded by 170 degrees: intersecting pairs",
      intersecting_pairs(folded(n, 170. * numbers::PI / 180., 0.)).size(),
      0);
    const std::vector<MeshTriangle> through = folded(n, numbers::PI, 0.1);
    const auto                      pairs   = intersecting_pairs(through);
    unsigned int                    across  = 0;
    const auto                      upper   = [&](const unsigned int t) {
      for (const auto v : through[t].vertices)
        if (v / n > n / 2)
          return true;
      return false;
    };
    for (const auto &[i, j] : pairs)
      across += upper(i) != upper(j) ? 1 : 0;
    check_above(out, "folded through itself: intersecting pairs", pairs.size(), 50);
    check_equal<std::size_t>(out,
                             "... pairs with one triangle from each half",
                             across,
                             pairs.size());
  }

  out << "3. random soups: BVH against every pair" << std::endl;
  {
    std::mt19937                           generator(5);
    std::uniform_real_distribution<double> uniform(0., 1.);
    unsigned int                           mismatches = 0, found = 0;
    for (unsigned int soup = 0; soup < 5; ++soup)
      {
        std::vector<MeshTriangle> triangles(300);
        for (unsigned int t = 0; t < triangles.size(); ++t)
          {
            const Point<3> centre(uniform(generator),
                                  uniform(generator),
                                  uniform(generator));
            for (unsigned int v = 0; v < 3; ++v)
              {
                triangles[t].corners[v] =
                  centre + 0.1 * Tensor<1, 3>({uniform(generator) - 0.5,
                                               uniform(generator) - 0.5,
                                               uniform(generator) - 0.5});
                triangles[t].vertices[v] = 3 * t + v;
              }
          }
        std::set<std::pair<unsigned int, unsigned int>> all;
        for (unsigned int i = 0; i < triangles.size(); ++i)
          for (unsigned int j = i + 1; j < triangles.size(); ++j)
            if (triangles_intersect(triangles[i].corners, triangles[j].corners))
              all.emplace(i, j);
        const auto pairs = intersecting_pairs(triangles);
        found += pairs.size();
        mismatches += std::set<std::pair<unsigned int, unsigned int>>(pairs.begin(),
                                                                      pairs.end()) != all
                        ? 1
                        : 0;
      }
    check_equal(out, "soups whose pairs differ from every pair's test", mismatches, 0u);
    check_above(out, "intersecting pairs found in the 5 soups", found, 20);
  }
  return finish_tally(out);
}
