#pragma once

// The mesh readers' test for a zero-area triangle (mesh/gmsh_reader.cc for the cloth,
// mesh/surface_mesh.cc for obstacles): degenerate if its area is at most 1e-12 times its
// longest edge squared, zero up to round-off whatever the mesh's unit.

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

namespace clothsim::mesh
{
  // "area A for a longest edge of L" if the triangle (p0, p1, p2) is degenerate, else
  // nothing.
  inline std::optional<std::string>
  degenerate_triangle(const dealii::Point<3> &p0,
                      const dealii::Point<3> &p1,
                      const dealii::Point<3> &p2)
  {
    constexpr double tolerance = 1e-12;
    const double     area      = 0.5 * dealii::cross_product_3d(p1 - p0, p2 - p0).norm();
    const double     longest_edge_square = std::max(
      {(p1 - p0).norm_square(), (p2 - p1).norm_square(), (p0 - p2).norm_square()});
    if (area > tolerance * longest_edge_square)
      return std::nullopt;
    std::ostringstream text;
    text << "area " << area << " for a longest edge of "
         << std::sqrt(longest_edge_square);
    return text.str();
  }
} // namespace clothsim::mesh
