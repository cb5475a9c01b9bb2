// mesh/surface_mesh: obstacle surfaces read from STL, OBJ and gmsh files.
// 1. The unit cube's surface (12 triangles, outward) as ASCII STL, binary STL (its
//    header starting with "solid"), OBJ (quads fan-triangulated; entries i, i/t, i//n,
//    i/t/n; negative indices) and gmsh .msh 2.2: 8 vertices after merging, 12
//    triangles, 18 edges, area 6 and enclosed volume 1 (the file's orientation kept)
//    within 1e-12; with scale 1e-3, area 6e-6.
// 2. The cube as an OpenCASCADE Box in a .geo, meshed in 2D: area 6 within 1e-9, a
//    closed surface (3 F = 2 E, V - E + F = 2).
// 3. meshes/table-top.geo: closed, inside its cylinder, area and volume of the cylinder
//    within 1e-3 relative (the volume positive: gmsh orients it outward), edges of
//    about 2 cm.
// 4. Bad input: an InputError whose message names the fault (missing file, unknown
//    extension, index out of range with its line, truncated binary STL, zero-area
//    triangle, malformed line, non-finite coordinate, no triangles, gmsh errors).

#include <deal.II/base/timer.h>

#include "io/input_error.h"
#include "mesh/surface_mesh.h"
#include "test_checks.h"

#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <fstream>

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  // The unit cube: vertex v at (v & 1, (v >> 1) & 1, (v >> 2) & 1); its faces as quads,
  // counter-clockwise seen from outside.
  Point<3>
  cube_vertex(const unsigned int v)
  {
    return Point<3>(v & 1, (v >> 1) & 1, (v >> 2) & 1);
  }

  const std::array<std::array<unsigned int, 4>, 6> cube_quads = {{{{0, 2, 3, 1}},
                                                                  {{4, 5, 7, 6}},
                                                                  {{0, 1, 5, 4}},
                                                                  {{2, 6, 7, 3}},
                                                                  {{0, 4, 6, 2}},
                                                                  {{1, 3, 7, 5}}}};

  // The cube's 12 triangles, two per quad.
  std::vector<std::array<unsigned int, 3>>
  cube_triangles()
  {
    std::vector<std::array<unsigned int, 3>> triangles;
    for (const auto &q : cube_quads)
      {
        triangles.push_back({{q[0], q[1], q[2]}});
        triangles.push_back({{q[0], q[2], q[3]}});
      }
    return triangles;
  }

  void
  write_file(const std::string &file, const std::string &content)
  {
    std::ofstream out(file, std::ios::binary);
    out << content;
  }

  std::string
  ascii_stl(const std::vector<std::array<unsigned int, 3>> &triangles)
  {
    std::ostringstream out;
    out << std::scientific << "solid cube\n";
    for (const auto &t : triangles)
      {
        // A normal is required by the format, not used by the reader.
        out << "  facet normal 0 0 0\n    outer loop\n";
        for (const unsigned int v : t)
          out << "      vertex " << cube_vertex(v) << '\n';
        out << "    endloop\n  endfacet\n";
      }
    out << "endsolid cube\n";
    return out.str();
  }

  // Appends the 4 little-endian bytes of `value`.
  void
  append_bytes(std::string &out, const std::uint32_t value)
  {
    for (unsigned int i = 0; i < 4; ++i)
      out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
  }

  void
  append_float(std::string &out, const float value)
  {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof(bits));
    append_bytes(out, bits);
  }

  std::string
  binary_stl(const std::vector<std::array<unsigned int, 3>> &triangles)
  {
    std::string out = "solid cube (a binary file, whatever its header says)";
    out.resize(80, ' ');
    append_bytes(out, triangles.size());
    for (const auto &t : triangles)
      {
        for (unsigned int d = 0; d < 3; ++d)
          append_float(out, 0.f);
        for (const unsigned int v : t)
          for (unsigned int d = 0; d < 3; ++d)
            append_float(out, cube_vertex(v)[d]);
        out += std::string(2, '\0');
      }
    return out;
  }

  // Quads with all kinds of face entries, after texture coordinates and normals.
  const std::string cube_obj = "# the unit cube\nmtllib cube.mtl\no cube\n"
                               "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                               "v 0 0 1\nv 1 0 1 # a comment\nv 0 1 1\nv 1 1 1\n"
                               "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                               "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\n"
                               "vn -1 0 0\nvn 1 0 0\n"
                               "usemtl wood\ns off\n"
                               "f 1 3 4 2\n"
                               "f 5/1 6/2 8/3 7/4\n"
                               "f 1//3 2//3 6//3 5//3\n"
                               "f -6/1/4 -2/2/4 -1/3/4 -5/4/4\n"
                               "f -8 -4 -2 -6\n"
                               "\tf  2/2/6 4/3/6 8/4/6 6/1/6 \r\n";

  std::string
  msh_2_2(const std::vector<std::array<unsigned int, 3>> &triangles)
  {
    std::ostringstream out;
    out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n8\n";
    for (unsigned int v = 0; v < 8; ++v)
      out << 10 + v << ' ' << cube_vertex(v) << '\n';
    out << "$EndNodes\n$Elements\n" << triangles.size() << '\n';
    for (unsigned int t = 0; t < triangles.size(); ++t)
      out << t + 1 << " 2 2 0 1 " << 10 + triangles[t][0] << ' ' << 10 + triangles[t][1]
          << ' ' << 10 + triangles[t][2] << '\n';
    out << "$EndElements\n";
    return out.str();
  }


  double
  area(const mesh::SurfaceMesh &surface)
  {
    double sum = 0;
    for (const auto &t : surface.triangles)
      sum += 0.5 * cross_product_3d(surface.vertices[t[1]] - surface.vertices[t[0]],
                                    surface.vertices[t[2]] - surface.vertices[t[0]])
                     .norm();
    return sum;
  }

  // The volume enclosed, positive for outward triangles (divergence theorem).
  double
  volume(const mesh::SurfaceMesh &surface)
  {
    double sum = 0;
    for (const auto &t : surface.triangles)
      sum += surface.vertices[t[0]] *
             cross_product_3d(surface.vertices[t[1]], surface.vertices[t[2]]) / 6.;
    return sum;
  }

  // Closed (each edge in two triangles: 3 F = 2 E), of genus 0 (V - E + F = 2), and
  // edges given once each, sorted, as sorted pairs.
  bool
  check_closed(ConditionalOStream      &out,
               const std::string       &name,
               const mesh::SurfaceMesh &s)
  {
    bool edges_sorted =
      std::is_sorted(s.edges.begin(), s.edges.end()) &&
      std::adjacent_find(s.edges.begin(), s.edges.end()) == s.edges.end();
    for (const auto &e : s.edges)
      edges_sorted &= e[0] < e[1];
    const long n_v = s.vertices.size(), n_e = s.edges.size(), n_f = s.triangles.size();
    bool       holds = check(out, edges_sorted, name + ": edges unique, sorted pairs");
    holds &= check_equal(out, name + ": 3 F - 2 E", 3 * n_f - 2 * n_e, 0L);
    holds &= check_equal(out, name + ": V - E + F", n_v - n_e + n_f, 2L);
    return holds;
  }

  bool
  check_cube(ConditionalOStream &out, const std::string &name, const std::string &file)
  {
    const mesh::SurfaceMesh s = mesh::read_surface_mesh(file);
    bool holds = check_equal(out, name + ": vertices", s.vertices.size(), std::size_t(8));
    holds &= check_equal(out, name + ": triangles", s.triangles.size(), std::size_t(12));
    holds &= check_equal(out, name + ": edges", s.edges.size(), std::size_t(18));
    holds &= check_closed(out, name, s);
    holds &= check_near(out, name + ": area", area(s), 6., 1e-12);
    holds &= check_near(out, name + ": volume", volume(s), 1., 1e-12);
    holds &= check_near(out,
                        name + ", scale 1e-3: area / 6e-6",
                        area(mesh::read_surface_mesh(file, 1e-3)) / 6e-6,
                        1.,
                        1e-12);
    return holds;
  }

  // read_surface_mesh(file) throws an InputError whose message holds all `words`.
  bool
  check_rejected(ConditionalOStream             &out,
                 const std::string              &name,
                 const std::string              &file,
                 const std::vector<std::string> &words)
  {
    std::string message = "no error";
    bool        holds   = false;
    try
      {
        mesh::read_surface_mesh(file);
      }
    catch (const InputError &error)
      {
        message = error.what();
        holds   = true;
        for (const std::string &word : words)
          holds &= message.find(word) != std::string::npos;
      }
    return check(out, holds, name + ": " + message);
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &pcout = env.pcout;
  const std::string   dir =
    scratch_directory("clothsim-surface-mesh-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = [&](const std::string &name) { return dir + "/" + name; };

  // 1. The cube in each format.
  const auto triangles = cube_triangles();
  write_file(path("cube-ascii.stl"), ascii_stl(triangles));
  write_file(path("cube-binary.STL"), binary_stl(triangles));
  write_file(path("cube.obj"), cube_obj);
  write_file(path("cube.msh"), msh_2_2(triangles));
  bool passed = check_cube(pcout, "ASCII STL", path("cube-ascii.stl"));
  passed &= check_cube(pcout, "binary STL", path("cube-binary.STL"));
  passed &= check_cube(pcout, "OBJ", path("cube.obj"));
  passed &= check_cube(pcout, "gmsh 2.2", path("cube.msh"));

  // 2. The cube meshed by gmsh.
  write_file(path("box.geo"),
             "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
             "Mesh.MeshSizeMax = 0.25;\n");
  {
    const mesh::SurfaceMesh box = mesh::read_surface_mesh(path("box.geo"));
    pcout << "  box.geo: " << box.vertices.size() << " vertices, " << box.triangles.size()
          << " triangles" << std::endl;
    passed &= check_at_least(pcout, "box.geo: triangles", box.triangles.size(), 24);
    passed &= check_closed(pcout, "box.geo", box);
    passed &= check_near(pcout, "box.geo: area", area(box), 6., 1e-9);
  }

  // 3. The table top.
  {
    Timer                   timer;
    const mesh::SurfaceMesh top =
      mesh::read_surface_mesh(source_path("meshes/table-top.geo"));
    timer.stop();
    pcout << "  table-top.geo: " << top.vertices.size() << " vertices, "
          << top.triangles.size() << " triangles, read in " << timer.wall_time() << " s"
          << std::endl;
    const double radius = 0.5, thickness = 0.04, pi = numbers::PI;
    double       max_radius = 0, min_z = 1, max_z = 0, edge_sum = 0, max_edge = 0;
    for (const Point<3> &p : top.vertices)
      {
        max_radius = std::max(max_radius, std::hypot(p[0], p[1]));
        min_z      = std::min(min_z, p[2]);
        max_z      = std::max(max_z, p[2]);
      }
    for (const auto &e : top.edges)
      {
        const double length = top.vertices[e[0]].distance(top.vertices[e[1]]);
        edge_sum += length;
        max_edge = std::max(max_edge, length);
      }
    passed &= check_closed(pcout, "table-top.geo", top);
    passed &=
      check_at_most(pcout, "table-top.geo: max radius", max_radius, radius + 1e-12);
    passed &= check_near(pcout, "table-top.geo: lowest z", min_z, 0.66, 1e-12);
    passed &= check_near(pcout, "table-top.geo: highest z", max_z, 0.70, 1e-12);
    passed &= check_near(pcout,
                         "table-top.geo: area / cylinder's",
                         area(top) / (2 * pi * radius * (radius + thickness)),
                         1.,
                         1e-3);
    passed &= check_near(pcout,
                         "table-top.geo: volume / cylinder's",
                         volume(top) / (pi * radius * radius * thickness),
                         1.,
                         1e-3);
    passed &= check_near(
      pcout, "table-top.geo: mean edge [m]", edge_sum / top.edges.size(), 0.02, 0.005);
    passed &= check_at_most(pcout, "table-top.geo: longest edge [m]", max_edge, 0.03);
  }

  // 4. Bad input.
  write_file(path("cube.ply"), "ply\n");
  std::string truncated = binary_stl(triangles);
  truncated.resize(truncated.size() - 10);
  write_file(path("truncated.stl"), truncated);
  write_file(path("index.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
  write_file(path("relative.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n");
  write_file(path("collinear.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  auto repeated  = triangles;
  repeated[1][2] = repeated[1][0];
  write_file(path("repeated.stl"), ascii_stl(repeated));
  std::string       short_vertex = ascii_stl(triangles);
  const std::size_t first_vertex = short_vertex.find("vertex");
  short_vertex.replace(first_vertex,
                       short_vertex.find('\n', first_vertex) - first_vertex,
                       "vertex 0 0");
  write_file(path("short-vertex.stl"), short_vertex);
  const std::string whole = ascii_stl(triangles);
  write_file(path("unfinished.stl"), whole.substr(0, whole.rfind('\n', 300) + 1));
  write_file(path("nan.obj"), "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  write_file(path("entry.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/a 2 3\n");
  write_file(path("points.obj"), "v 0 0 0\nv 1 0 0\n");
  write_file(path("syntax.geo"), "Point(1) = {0, 0, 0;\n");
  write_file(path("quads.geo"),
             "SetFactory(\"OpenCASCADE\");\nRectangle(1) = {0, 0, 0, 1, 1};\n"
             "Mesh.RecombineAll = 1;\n");

  passed &= check_rejected(pcout, "missing file", path("no-such.stl"), {"not found"});
  passed &=
    check_rejected(pcout, "unknown extension", path("cube.ply"), {"unknown extension"});
  passed &= check_rejected(pcout,
                           "truncated binary STL",
                           path("truncated.stl"),
                           {"truncated binary STL"});
  passed &= check_rejected(pcout,
                           "OBJ index out of range",
                           path("index.obj"),
                           {"line 5", "out of range"});
  passed &= check_rejected(pcout,
                           "OBJ relative index out of range",
                           path("relative.obj"),
                           {"line 4", "-4"});
  passed &= check_rejected(pcout,
                           "collinear OBJ triangle",
                           path("collinear.obj"),
                           {"line 4", "zero-area"});
  passed &= check_rejected(pcout,
                           "STL triangle using a vertex twice",
                           path("repeated.stl"),
                           {"facet 2", "zero-area"});
  passed &= check_rejected(pcout,
                           "STL vertex of 2 coordinates",
                           path("short-vertex.stl"),
                           {"line 4", "3 coordinates"});
  passed &= check_rejected(pcout,
                           "unfinished ASCII STL",
                           path("unfinished.stl"),
                           {"ends inside"});
  passed &=
    check_rejected(pcout, "NaN in OBJ", path("nan.obj"), {"line 2", "non-finite"});
  passed &= check_rejected(pcout,
                           "malformed OBJ face entry",
                           path("entry.obj"),
                           {"line 4", "'1/a'"});
  passed &=
    check_rejected(pcout, "OBJ without faces", path("points.obj"), {"no triangles"});
  passed &= check_rejected(pcout, ".geo syntax error", path("syntax.geo"), {"gmsh"});
  passed &=
    check_rejected(pcout, "quadrilaterals", path("quads.geo"), {"only 3-node triangles"});

  std::filesystem::remove_all(dir);
  return finish(pcout, passed);
}
