// read_surface_mesh(): each format is read into a triangle soup (corner points, and how
// to name each triangle in errors: STL and OBJ in mesh/surface_mesh_formats.cc, gmsh
// here); one pipeline then scales, checks and merges it and lists the edges.

#include "mesh/surface_mesh.h"

#include "io/input_error.h"
#include "io/input_file.h"
#include "mesh/child_process.h"
#include "mesh/degenerate_triangle.h"
#include "mesh/gmsh_session.h"
#include "mesh/surface_mesh_detail.h"

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <unordered_map>

namespace clothsim::mesh
{
  using namespace detail;


  namespace
  {
    // ---------------------------------------------------------------------------------
    // gmsh

    // The 3-node triangles of gmsh's current model; other surface elements are an error.
    Soup
    triangles_of_model(const std::string &file)
    {
      constexpr int gmsh_triangle_type = 2;

      Soup soup;
      soup.kind = "element";
      std::unordered_map<std::size_t, std::size_t> point_of_node;
      {
        std::vector<std::size_t> node_tags;
        std::vector<double>      coordinates, parametric_coordinates;
        gmsh::model::mesh::getNodes(
          node_tags, coordinates, parametric_coordinates, -1, -1, false, false);
        for (std::size_t i = 0; i < node_tags.size(); ++i)
          {
            point_of_node[node_tags[i]] = soup.points.size();
            soup.points.emplace_back(coordinates[3 * i],
                                     coordinates[3 * i + 1],
                                     coordinates[3 * i + 2]);
          }
      }

      std::vector<int>                      types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gmsh::model::mesh::getElements(types, element_tags, node_tags, 2, -1);
      for (std::size_t k = 0; k < types.size(); ++k)
        {
          if (element_tags[k].empty())
            continue;
          if (types[k] != gmsh_triangle_type)
            throw InputError(file,
                             "element " + std::to_string(element_tags[k][0]),
                             "a surface element of gmsh type " +
                               std::to_string(types[k]) +
                               "; only 3-node triangles (type 2) are read");
          for (std::size_t e = 0; e < element_tags[k].size(); ++e)
            {
              std::array<std::size_t, 3> corners;
              for (unsigned int c = 0; c < 3; ++c)
                {
                  const auto point = point_of_node.find(node_tags[k][3 * e + c]);
                  if (point == point_of_node.end())
                    throw InputError(file,
                                     "element " + std::to_string(element_tags[k][e]),
                                     "node " + std::to_string(node_tags[k][3 * e + c]) +
                                       " is not defined");
                  corners[c] = point->second;
                }
              soup.triangles.push_back(corners);
              soup.numbers.push_back(element_tags[k][e]);
            }
        }
      return soup;
    }

    // Reads the .msh, or meshes the .geo in 2D; first in a child process (gmsh crashes
    // on some malformed files: mesh/child_process.h), then here.
    Soup
    read_with_gmsh(const std::string &file, const bool geo)
    {
      const auto read = [&]() {
        std::unique_ptr<GmshSession> session;
        call_gmsh(file, "gmsh cannot start", [&]() {
          session = std::make_unique<GmshSession>();
        });
        if (geo)
          {
            // Errors through the log, not thrown: a .geo syntax error thrown out of
            // gmsh's parser leaves it broken for later .geo files in this process.
            const std::string context = "gmsh cannot mesh it";
            call_gmsh(file, context, [&]() {
              const GmshLog log;
              gmsh::option::setNumber("General.AbortOnError", 0);
              gmsh::open(file);
              log.throw_first_error(file, context);
              gmsh::model::mesh::generate(2);
              log.throw_first_error(file, context);
              gmsh::option::setNumber("General.AbortOnError", 2);
            });
          }
        else
          call_gmsh(file, "gmsh cannot read it", [&]() { gmsh::open(file); });
        Soup soup;
        call_gmsh(file, "gmsh cannot read it", [&]() {
          soup = triangles_of_model(file);
        });
        return soup;
      };
      run_in_child_process(file, geo ? "gmsh meshing it" : "gmsh reading it", [&]() {
        read();
      });
      return read();
    }


    // ---------------------------------------------------------------------------------
    // From the soup to the mesh

    SurfaceMesh
    build_surface_mesh(const std::string &file, const Soup &soup, const double scale)
    {
      if (soup.triangles.empty())
        throw InputError(file, "", "no triangles in the file");

      constexpr unsigned int unset = std::numeric_limits<unsigned int>::max();
      SurfaceMesh            mesh;
      // Vertex of each soup point, and of each coordinate triple seen.
      std::vector<unsigned int> vertex_of_point(soup.points.size(), unset);
      std::map<std::array<double, 3>, unsigned int> vertex_of_coordinates;
      mesh.triangles.resize(soup.triangles.size());
      for (std::size_t t = 0; t < soup.triangles.size(); ++t)
        {
          for (unsigned int c = 0; c < 3; ++c)
            {
              const std::size_t point = soup.triangles[t][c];
              if (vertex_of_point[point] == unset)
                {
                  const Point<3> position = scale * soup.points[point];
                  for (unsigned int d = 0; d < 3; ++d)
                    if (!std::isfinite(position[d]))
                      {
                        std::ostringstream message;
                        message << "corner " << c + 1 << " has a non-finite coordinate ("
                                << soup.points[point] << ")";
                        if (std::isfinite(soup.points[point][d]))
                          message << " after scaling by " << scale;
                        throw InputError(file, soup.name(t), message.str());
                      }
                  const auto [entry, inserted] = vertex_of_coordinates.emplace(
                    std::array<double, 3>{{position[0], position[1], position[2]}},
                    mesh.vertices.size());
                  if (inserted)
                    mesh.vertices.push_back(position);
                  vertex_of_point[point] = entry->second;
                }
              mesh.triangles[t][c] = vertex_of_point[point];
            }

          const std::array<unsigned int, 3> &triangle = mesh.triangles[t];
          if (triangle[0] == triangle[1] || triangle[1] == triangle[2] ||
              triangle[2] == triangle[0])
            throw InputError(file,
                             soup.name(t),
                             "zero-area (degenerate) triangle: two of its corners are "
                             "the same vertex");
          if (const auto degenerate = degenerate_triangle(mesh.vertices[triangle[0]],
                                                          mesh.vertices[triangle[1]],
                                                          mesh.vertices[triangle[2]]))
            throw InputError(file,
                             soup.name(t),
                             "zero-area (degenerate) triangle: " + *degenerate);
        }

      mesh.edges.reserve(3 * mesh.triangles.size());
      for (const std::array<unsigned int, 3> &triangle : mesh.triangles)
        for (unsigned int i = 0; i < 3; ++i)
          mesh.edges.push_back({{std::min(triangle[i], triangle[(i + 1) % 3]),
                                 std::max(triangle[i], triangle[(i + 1) % 3])}});
      std::sort(mesh.edges.begin(), mesh.edges.end());
      mesh.edges.erase(std::unique(mesh.edges.begin(), mesh.edges.end()),
                       mesh.edges.end());
      mesh.edges.shrink_to_fit();
      return mesh;
    }


    std::string
    read_file(const std::string &file)
    {
      std::ifstream in(file, std::ios::binary);
      if (!in)
        throw InputError(file, "", "cannot be opened for reading");
      std::string content((std::istreambuf_iterator<char>(in)),
                          std::istreambuf_iterator<char>());
      if (in.bad())
        throw InputError(file, "", "cannot be read");
      return content;
    }
  } // namespace


  SurfaceMesh
  read_surface_mesh(const std::string &file, const double scale)
  {
    AssertThrow(scale > 0 && std::isfinite(scale),
                ExcMessage("the scale of a surface mesh must be positive and finite"));

    std::string extension = std::filesystem::path(file).extension().string();
    for (char &c : extension)
      c = std::tolower(static_cast<unsigned char>(c));
    if (extension != ".stl" && extension != ".obj" && extension != ".msh" &&
        extension != ".geo")
      throw InputError(file,
                       "",
                       "unknown extension '" + extension +
                         "' for a surface mesh: .stl, .obj, .msh or .geo expected");

    const std::filesystem::file_type type = input_file_type(file);
    if (type == std::filesystem::file_type::not_found)
      throw InputError(file, "", "surface mesh file not found");
    if (type != std::filesystem::file_type::regular)
      throw InputError(file, "", "not a regular file");

    Soup soup;
    if (extension == ".stl")
      soup = read_stl(file, read_file(file));
    else if (extension == ".obj")
      soup = read_obj(file, read_file(file));
    else
      soup = read_with_gmsh(file, extension == ".geo");
    return build_surface_mesh(file, soup, scale);
  }
} // namespace clothsim::mesh
