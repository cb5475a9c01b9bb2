// The mesh's physical groups by name: line groups as boundary ids, surface groups as
// material ids, point groups as coordinates; each checked against the triangles.

#include "mesh/gmsh_reader.h"

#include <deal.II/base/types.h>

#include "io/input_error.h"
#include "mesh/gmsh_reader_detail.h"

#include <set>

namespace clothsim::mesh
{
  std::vector<std::string>
  MeshGroups::all_names() const
  {
    std::set<std::string> names;
    for (const auto &group : line_groups)
      names.insert(group.first);
    for (const auto &group : point_groups)
      names.insert(group.first);
    for (const auto &group : surface_groups)
      names.insert(group.first);
    return {names.begin(), names.end()};
  }


  namespace detail
  {
    std::map<std::pair<unsigned int, unsigned int>, types::boundary_id>
    add_line_groups(const std::string                                   &msh_file,
                    const RawMesh                                       &raw,
                    const std::unordered_map<std::size_t, unsigned int> &vertex_of_node,
                    const Edges                                         &edges,
                    MeshGroups                                          &groups)
    {
      std::map<std::pair<unsigned int, unsigned int>, types::boundary_id> boundary_ids;
      std::map<types::boundary_id, std::string>                           group_of_id;
      for (const RawLineGroup &group : raw.line_groups)
        {
          if (group.tag < 1 ||
              static_cast<unsigned long long>(group.tag) >=
                static_cast<unsigned long long>(numbers::internal_face_boundary_id))
            throw InputError(msh_file,
                             group.name,
                             "physical tag " + std::to_string(group.tag) +
                               " cannot serve as a boundary id (must be in 1.." +
                               std::to_string(numbers::internal_face_boundary_id - 1) +
                               ")");
          const auto id = static_cast<types::boundary_id>(group.tag);
          if (!groups.line_groups.emplace(group.name, id).second)
            throw InputError(msh_file,
                             group.name,
                             "two line groups have this name (physical tags " +
                               std::to_string(groups.line_groups[group.name]) + " and " +
                               std::to_string(group.tag) + ")");
          group_of_id[id] = group.name;

          for (const RawLine &line : group.lines)
            {
              const std::string line_name = "line " + std::to_string(line.tag) + " " +
                                            edge_text(line.nodes[0], line.nodes[1]);
              const auto v0   = vertex_of_node.find(line.nodes[0]);
              const auto v1   = vertex_of_node.find(line.nodes[1]);
              const auto edge = (v0 == vertex_of_node.end() || v1 == vertex_of_node.end())
                                  ? edges.end()
                                  : edges.find(edge_key(v0->second, v1->second));
              if (edge == edges.end())
                throw InputError(msh_file,
                                 group.name,
                                 line_name + " is not an edge of the triangles");
              if (edge->second.size() != 1)
                throw InputError(msh_file,
                                 group.name,
                                 line_name +
                                   " is an interior edge; line groups must lie on "
                                   "the boundary");
              const auto [previous, inserted] = boundary_ids.emplace(edge->first, id);
              if (!inserted && previous->second != id)
                throw InputError(msh_file,
                                 group.name,
                                 line_name + " is also in line group '" +
                                   group_of_id[previous->second] +
                                   "'; a boundary edge can be in one line group only");
            }
        }
      return boundary_ids;
    }


    void
    add_surface_groups(const std::string        &msh_file,
                       const RawMesh            &raw,
                       std::vector<CellData<2>> &cells,
                       MeshGroups               &groups)
    {
      const unsigned int                            n_cells = raw.triangles.size();
      std::unordered_map<std::size_t, unsigned int> cell_of_triangle;
      for (unsigned int c = 0; c < n_cells; ++c)
        cell_of_triangle.emplace(raw.triangles[c].tag, c);
      // Surface group of each cell (index into raw.surface_groups), or none.
      constexpr unsigned int    no_group = numbers::invalid_unsigned_int;
      std::vector<unsigned int> group_of_cell(n_cells, no_group);
      for (unsigned int g = 0; g < raw.surface_groups.size(); ++g)
        {
          const RawSurfaceGroup &group = raw.surface_groups[g];
          if (group.tag < 1 ||
              static_cast<unsigned long long>(group.tag) >=
                static_cast<unsigned long long>(numbers::invalid_material_id))
            throw InputError(msh_file,
                             group.name,
                             "physical tag " + std::to_string(group.tag) +
                               " cannot serve as a material id (must be in 1.." +
                               std::to_string(numbers::invalid_material_id - 1) + ")");
          const auto id = static_cast<types::material_id>(group.tag);
          if (!groups.surface_groups.emplace(group.name, id).second)
            throw InputError(msh_file,
                             group.name,
                             "two surface groups have this name (physical tags " +
                               std::to_string(groups.surface_groups[group.name]) +
                               " and " + std::to_string(group.tag) + ")");

          for (const std::size_t triangle : group.triangles)
            {
              const auto cell = cell_of_triangle.find(triangle);
              if (cell == cell_of_triangle.end())
                throw InputError(msh_file,
                                 group.name,
                                 "element " + std::to_string(triangle) +
                                   " is not one of the mesh's triangles");
              unsigned int &previous = group_of_cell[cell->second];
              if (previous != no_group && previous != g)
                throw InputError(msh_file,
                                 group.name,
                                 "triangle " + std::to_string(triangle) +
                                   " is also in surface group '" +
                                   raw.surface_groups[previous].name +
                                   "'; a triangle can be in one surface group only");
              previous                        = g;
              cells[cell->second].material_id = id;
            }
        }
    }


    void
    add_point_groups(const std::string                                   &msh_file,
                     const RawMesh                                       &raw,
                     const std::unordered_map<std::size_t, unsigned int> &vertex_of_node,
                     const std::vector<Point<3>>                         &vertices,
                     MeshGroups                                          &groups)
    {
      for (const RawPointGroup &group : raw.point_groups)
        {
          std::vector<Point<3>> points;
          for (const std::size_t node : group.nodes)
            {
              const auto vertex = vertex_of_node.find(node);
              if (vertex == vertex_of_node.end())
                throw InputError(msh_file,
                                 group.name,
                                 "node " + std::to_string(node) +
                                   " is not a vertex of any triangle");
              points.push_back(vertices[vertex->second]);
            }
          if (!groups.point_groups.emplace(group.name, std::move(points)).second)
            throw InputError(msh_file, group.name, "two point groups have this name");
        }
    }
  } // namespace detail
} // namespace clothsim::mesh
