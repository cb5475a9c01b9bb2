#pragma once

// The area of a surface's shadow on the horizontal plane (its projection along z): the
// area of the union of the projected triangles, so that folds lying over each other count
// once. Measured by sampling: the triangles' bounding rectangle is divided into
// `resolution` x `resolution` cells and a cell counts if its centre lies in a triangle.
// The error is of the order of the outline's length times the cell size, with
// cancellation (boundary cells count in or out at random): for a 30 cm specimen at 1,024
// cells per side, about 1e-4 of the area.

#include <deal.II/base/point.h>

#include <array>
#include <vector>

namespace clothsim::mesh
{
  using namespace dealii;

  // Triangles as their three (x, y) corners, m; returns m².
  double
  projected_area(const std::vector<std::array<Point<2>, 3>> &triangles,
                 const unsigned int                          resolution = 1024);
} // namespace clothsim::mesh
