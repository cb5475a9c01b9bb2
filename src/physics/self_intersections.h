#pragma once

// An independent check that the cloth does not pass through itself: every pair of the
// mesh's triangles that share no vertex and intersect (touching counts). Broad phase: a
// BVH of the triangles' boxes (physics/aabb_tree.h); narrow phase: two triangles in
// general position intersect exactly when an edge of one meets the other, decided by
// the signs of orientation determinants (six times signed tetrahedron volumes); an edge
// that lies in the other triangle's plane, and a coplanar pair, are decided in that plane
// (projected along the normal's largest component) by orientation tests of the 2D
// points. Tolerance: a point within 1e-9 of the pair's size (its longest edge) from a
// triangle's plane counts as in the plane; otherwise the determinants' signs are taken
// as computed in floating point, so pairs within round-off of touching may be reported
// either way.

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <array>
#include <utility>
#include <vector>

namespace clothsim::physics
{
  using namespace dealii;

  // One triangle of the whole mesh: its corners (m) and its vertices' ids (any numbers
  // that are equal exactly for the same vertex).
  struct MeshTriangle
  {
    std::array<Point<3>, 3>                corners;
    std::array<types::global_dof_index, 3> vertices;
  };

  // Whether the closed triangles a and b have a point in common.
  bool
  triangles_intersect(const std::array<Point<3>, 3> &a, const std::array<Point<3>, 3> &b);

  // The pairs (i, j), i < j, of `triangles` that share no vertex and intersect, sorted.
  std::vector<std::pair<unsigned int, unsigned int>>
  intersecting_pairs(const std::vector<MeshTriangle> &triangles);
} // namespace clothsim::physics
