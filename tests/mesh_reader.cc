// Unit test of clothsim::mesh::read_gmsh: reads the meshes in the directory given as
// argv[1] (tests/data), checks cell and vertex counts, areas, boundary ids, material ids
// (surface groups) and point groups, that bad meshes are rejected with a telling
// InputError, and that a .msh is generated from a .geo.

#include <deal.II/grid/tria.h>

#include "io/input_error.h"
#include "mesh/gmsh_reader.h"
#include "test_support.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace clothsim;
using namespace clothsim::test;

namespace
{
  double
  total_area(const Triangulation<2, 3> &triangulation)
  {
    double area = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      area += 0.5 * cross_product_3d(cell->vertex(1) - cell->vertex(0),
                                     cell->vertex(2) - cell->vertex(0))
                      .norm();
    return area;
  }


  // Number of active boundary faces per boundary id.
  std::map<types::boundary_id, unsigned int>
  count_boundary_faces(const Triangulation<2, 3> &triangulation)
  {
    std::map<types::boundary_id, unsigned int> counts;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          ++counts[cell->face(f)->boundary_id()];
    return counts;
  }


  // Number of active cells per material id.
  std::map<types::material_id, unsigned int>
  count_material_ids(const Triangulation<2, 3> &triangulation)
  {
    std::map<types::material_id, unsigned int> counts;
    for (const auto &cell : triangulation.active_cell_iterators())
      ++counts[cell->material_id()];
    return counts;
  }


  // True if the center of every active cell with material id `id` lies in the box
  // [x_min, x_max] x [y_min, y_max].
  bool
  cells_in_box(const Triangulation<2, 3> &triangulation,
               const types::material_id   id,
               const double               x_min,
               const double               x_max,
               const double               y_min,
               const double               y_max)
  {
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->material_id() == id)
        {
          const Point<3> center = cell->center();
          if (center[0] < x_min || center[0] > x_max || center[1] < y_min ||
              center[1] > y_max)
            return false;
        }
    return true;
  }


  // Total length of the active boundary faces with boundary id `id`.
  double
  boundary_length(const Triangulation<2, 3> &triangulation, const types::boundary_id id)
  {
    double length = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == id)
          length += (cell->face(f)->vertex(1) - cell->face(f)->vertex(0)).norm();
    return length;
  }


  // True if every active boundary face with boundary id `id` lies on the plane
  // x[axis]=value.
  bool
  boundary_faces_on(const Triangulation<2, 3> &triangulation,
                    const types::boundary_id   id,
                    const unsigned int         axis,
                    const double               value)
  {
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == id)
          for (const unsigned int v : {0u, 1u})
            if (std::abs(cell->face(f)->vertex(v)[axis] - value) > 1e-14)
              return false;
    return true;
  }


  bool
  contains(const std::string &text, const std::string &word)
  {
    return text.find(word) != std::string::npos;
  }


  // read_gmsh(file) must throw an InputError naming the file and containing all `words`.
  void
  check_rejected(ConditionalOStream             &out,
                 const std::string              &file,
                 const std::vector<std::string> &words)
  {
    const std::string name = std::filesystem::path(file).filename().string();
    try
      {
        Triangulation<2, 3> triangulation;
        mesh::read_gmsh(file, triangulation);
        check(out, false, name + ": rejected (but it was accepted)");
      }
    catch (const InputError &error)
      {
        const std::string message = error.what();
        bool              ok      = contains(message, file) && error.file == file;
        for (const std::string &word : words)
          ok = ok && contains(message, word);
        check(out, ok, name + ": rejected with \"" + message + "\"");
      }
  }


  void
  test_square(ConditionalOStream &out, const std::string &data)
  {
    out << "square.msh (gmsh 2.2, 3x3 nodes + 1 unused node, 8 triangles):" << std::endl;
    // Surface groups: "half" (tag 32) = the 4 triangles of the bottom half, "cloth" (tag
    // 31) = the 2 of the top-left quarter; the 2 of the top-right quarter are in none.
    Triangulation<2, 3>    triangulation;
    const mesh::MeshGroups groups = mesh::read_gmsh(data + "/square.msh", triangulation);

    check_equal(out, "cells", triangulation.n_active_cells(), 8u);
    check_equal(out, "vertices", triangulation.n_vertices(), 9u);
    check_equal(out, "used vertices", triangulation.n_used_vertices(), 9u);
    check_near(out, "total area", total_area(triangulation), 1.0, 1e-12);
    bool all_triangles = true;
    for (const auto &cell : triangulation.active_cell_iterators())
      all_triangles = all_triangles && cell->reference_cell() == ReferenceCells::Triangle;
    check(out, all_triangles, "all cells are triangles");

    check_equal(out, "line groups", groups.line_groups.size(), std::size_t(3));
    check(out,
          groups.line_groups.count("left") == 1 && groups.line_groups.at("left") == 11,
          "line group 'left' has boundary id 11 (its physical tag)");
    check(out,
          groups.line_groups.count("bottom") == 1 &&
            groups.line_groups.at("bottom") == 12,
          "line group 'bottom' has boundary id 12");
    check(out,
          groups.line_groups.count("13") == 1 && groups.line_groups.at("13") == 13,
          "unnamed line group 13 is called '13' with boundary id 13");
    const std::vector<std::string> expected_names = {
      "13", "bottom", "cloth", "corner", "half", "left"};
    check(out,
          groups.all_names() == expected_names,
          "all_names() = {13, bottom, cloth, corner, half, left}");

    check_equal(out, "surface groups", groups.surface_groups.size(), std::size_t(2));
    check(out,
          groups.surface_groups.count("cloth") == 1 &&
            groups.surface_groups.at("cloth") == 31,
          "surface group 'cloth' has material id 31 (its physical tag)");
    check(out,
          groups.surface_groups.count("half") == 1 &&
            groups.surface_groups.at("half") == 32,
          "surface group 'half' has material id 32");
    auto materials = count_material_ids(triangulation);
    check_equal(out, "cells with material id 31 (cloth)", materials[31], 2u);
    check_equal(out, "cells with material id 32 (half)", materials[32], 4u);
    check_equal(out, "cells with material id 0 (in no group)", materials[0], 2u);
    check_equal(out, "distinct material ids", materials.size(), std::size_t(3));
    check(out,
          cells_in_box(triangulation, 32, 0, 1, 0, 0.5),
          "cells with material id 32 lie in the bottom half");
    check(out,
          cells_in_box(triangulation, 31, 0, 0.5, 0.5, 1),
          "cells with material id 31 lie in the top-left quarter");
    check(out,
          cells_in_box(triangulation, 0, 0.5, 1, 0.5, 1),
          "cells with material id 0 lie in the top-right quarter");

    auto counts = count_boundary_faces(triangulation);
    check_equal(out, "boundary faces with id 11 (left)", counts[11], 2u);
    check_equal(out, "boundary faces with id 12 (bottom)", counts[12], 2u);
    check_equal(out, "boundary faces with id 13", counts[13], 2u);
    check_equal(out, "boundary faces with id 0 (top, in no group)", counts[0], 2u);
    check_equal(out, "distinct boundary ids", counts.size(), std::size_t(4));
    check(out,
          boundary_faces_on(triangulation, 11, 0, 0.0),
          "faces with id 11 lie on x = 0");
    check(out,
          boundary_faces_on(triangulation, 12, 1, 0.0),
          "faces with id 12 lie on y = 0");
    check(out,
          boundary_faces_on(triangulation, 0, 1, 1.0),
          "faces with id 0 lie on y = 1");
    check_near(out, "length of 'left'", boundary_length(triangulation, 11), 1.0, 1e-14);

    check_equal(out, "point groups", groups.point_groups.size(), std::size_t(1));
    check(out,
          groups.point_groups.count("corner") == 1 &&
            groups.point_groups.at("corner").size() == 1 &&
            groups.point_groups.at("corner")[0] == Point<3>(1, 1, 0),
          "point group 'corner' = {(1, 1, 0)}");

    triangulation.refine_global(1);
    counts = count_boundary_faces(triangulation);
    out << "after refine_global(1):" << std::endl;
    check_equal(out, "cells", triangulation.n_active_cells(), 32u);
    check_near(out, "total area", total_area(triangulation), 1.0, 1e-12);
    check_equal(out, "boundary faces with id 11 (left)", counts[11], 4u);
    check_equal(out, "boundary faces with id 12 (bottom)", counts[12], 4u);
    check_equal(out, "boundary faces with id 0", counts[0], 4u);
    check(out,
          boundary_faces_on(triangulation, 11, 0, 0.0),
          "faces with id 11 lie on x = 0");
    check_near(out, "length of 'left'", boundary_length(triangulation, 11), 1.0, 1e-14);
    materials = count_material_ids(triangulation);
    check_equal(out, "cells with material id 31 (cloth)", materials[31], 8u);
    check_equal(out, "cells with material id 32 (half)", materials[32], 16u);
    check_equal(out, "cells with material id 0 (in no group)", materials[0], 8u);
    check_equal(out, "distinct material ids", materials.size(), std::size_t(3));
    check(out,
          cells_in_box(triangulation, 32, 0, 1, 0, 0.5),
          "cells with material id 32 lie in the bottom half");
    check(out,
          cells_in_box(triangulation, 31, 0, 0.5, 0.5, 1),
          "cells with material id 31 lie in the top-left quarter");
  }


  void
  test_bad_meshes(ConditionalOStream &out, const std::string &data)
  {
    out << "bad meshes:" << std::endl;
    check_rejected(out, data + "/quad.msh", {"Quadrilateral", "element 7"});
    check_rejected(out, data + "/degenerate.msh", {"degenerate", "triangle 5"});
    check_rejected(out,
                   data + "/flipped.msh",
                   {"not consistently oriented", "triangles 1 and 2"});
    check_rejected(out, data + "/interior_line.msh", {"seam", "interior", "boundary"});
    check_rejected(out, data + "/nonmanifold.msh", {"non-manifold", "1, 2, 3"});
    check_rejected(out,
                   data + "/overlapping_surfaces.msh",
                   {"back", "triangle 1", "also in surface group 'front'"});
    check_rejected(out, data + "/no_such_mesh.msh", {"not found"});
  }


  void
  test_generation_from_geo(ConditionalOStream &out)
  {
    namespace fs = std::filesystem;
    out << "generation from a .geo:" << std::endl;
    const fs::path directory =
      fs::temp_directory_path() / ("clothsim_mesh_reader_" + std::to_string(::getpid()));
    fs::remove_all(directory);
    fs::create_directories(directory);
    {
      std::ofstream geo(directory / "square.geo");
      geo << "lc = 0.25;\n"
             "Point(1) = {0, 0, 0, lc};\n"
             "Point(2) = {1, 0, 0, lc};\n"
             "Point(3) = {1, 1, 0, lc};\n"
             "Point(4) = {0, 1, 0, lc};\n"
             "Line(1) = {1, 2};\n"
             "Line(2) = {2, 3};\n"
             "Line(3) = {3, 4};\n"
             "Line(4) = {4, 1};\n"
             "Curve Loop(1) = {1, 2, 3, 4};\n"
             "Plane Surface(1) = {1};\n"
             "Physical Curve(\"left\", 7) = {4};\n"
             "Physical Point(\"origin\", 8) = {1};\n"
             "Physical Surface(\"cloth\", 9) = {1};\n";
    }
    // A .geo with a syntax error first: rejected, and gmsh must parse the next .geo fine.
    {
      std::ofstream geo(directory / "broken.geo");
      geo << "Point(1) = {0, 0, 0, 0.25}\nLine(1) = {1, 2};\n";
    }
    check_rejected(out,
                   (directory / "broken.msh").string(),
                   {"broken.geo", "syntax error"});

    const std::string msh_file = (directory / "square.msh").string();
    check(out, !fs::exists(msh_file), "square.msh does not exist before");

    try
      {
        Triangulation<2, 3>    triangulation;
        const mesh::MeshGroups groups = mesh::read_gmsh(msh_file, triangulation);
        check(out, fs::exists(msh_file), "square.msh exists after");
        const auto written = fs::last_write_time(msh_file);
        out << "  (" << triangulation.n_active_cells() << " cells, "
            << triangulation.n_vertices() << " vertices)" << std::endl;
        check(out, triangulation.n_active_cells() > 8, "more than 8 cells");
        check_near(out, "total area", total_area(triangulation), 1.0, 1e-12);
        check(out,
              groups.line_groups.count("left") == 1 && groups.line_groups.at("left") == 7,
              "line group 'left' has boundary id 7");
        check_near(
          out, "length of 'left'", boundary_length(triangulation, 7), 1.0, 1e-12);
        check(out,
              boundary_faces_on(triangulation, 7, 0, 0.0),
              "faces with id 7 lie on x = 0");
        check(out,
              groups.point_groups.count("origin") == 1 &&
                groups.point_groups.at("origin").size() == 1 &&
                groups.point_groups.at("origin")[0] == Point<3>(0, 0, 0),
              "point group 'origin' = {(0, 0, 0)}");
        check(out,
              groups.surface_groups.count("cloth") == 1 &&
                groups.surface_groups.at("cloth") == 9,
              "surface group 'cloth' has material id 9");
        const auto materials = count_material_ids(triangulation);
        check(out,
              materials.size() == 1 && materials.begin()->first == 9,
              "all cells have material id 9");

        // A second read takes the existing .msh as it is.
        Triangulation<2, 3> again;
        mesh::read_gmsh(msh_file, again);
        check_equal(out,
                    "cells when read again",
                    again.n_active_cells(),
                    triangulation.n_active_cells());
        check(out, fs::last_write_time(msh_file) == written, "square.msh not rewritten");
      }
    catch (const std::exception &error)
      {
        check(out, false, std::string("generation threw: ") + error.what());
      }
    fs::remove_all(directory);
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment env(argc, argv);
  if (argc != 2)
    {
      std::cerr << "usage: " << argv[0] << " <directory with the test meshes>"
                << std::endl;
      return 2;
    }
  const std::string data = argv[1];

  try
    {
      test_square(env.pcout, data);
      test_bad_meshes(env.pcout, data);
      test_generation_from_geo(env.pcout);
    }
  catch (const std::exception &error)
    {
      check(env.pcout, false, std::string("unexpected exception: ") + error.what());
    }
  return finish_tally(env.pcout);
}
