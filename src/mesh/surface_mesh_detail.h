#pragma once

// The parts of mesh/surface_mesh shared by its files: the triangles of a file as read,
// before they are checked and merged, and the readers of STL and OBJ files
// (mesh/surface_mesh_formats.cc). Not part of the interface.

#include <deal.II/base/point.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace clothsim::mesh::detail
{
  using namespace dealii;

  // Triangles as read: corners index `points`. Triangle t is named in errors as
  // "<kind> <numbers[t]>", followed by " (line <lines[t]>)" if lines are given.
  struct Soup
  {
    std::vector<Point<3>>                   points;
    std::vector<std::array<std::size_t, 3>> triangles;
    std::string                             kind;
    std::vector<std::size_t>                numbers;
    std::vector<std::size_t>                lines;

    std::string
    name(const std::size_t t) const
    {
      std::string text = kind + " " + std::to_string(numbers[t]);
      if (!lines.empty())
        text += " (line " + std::to_string(lines[t]) + ")";
      return text;
    }
  };


  // The triangles of an STL file (ASCII or binary) whose bytes are `content`; `file`
  // names it in errors.
  Soup
  read_stl(const std::string &file, const std::string &content);

  // The triangles of an OBJ file whose text is `text` (faces fan-triangulated).
  Soup
  read_obj(const std::string &file, const std::string &text);
} // namespace clothsim::mesh::detail
