// read_gmsh(): the mesh as gmsh gives it, checked (vertices, cells, edges) and built into
// a Triangulation with its groups. Running gmsh is in mesh/gmsh_session.cc and
// mesh/gmsh_model.cc, the groups in mesh/gmsh_groups.cc.

#include "mesh/gmsh_reader.h"

#include "io/input_error.h"
#include "mesh/degenerate_triangle.h"
#include "mesh/gmsh_reader_detail.h"

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace clothsim::mesh
{
  using namespace detail;


  namespace detail
  {
    std::string
    edge_text(const std::size_t node_0, const std::size_t node_1)
    {
      return "(nodes " + std::to_string(node_0) + "-" + std::to_string(node_1) + ")";
    }

    std::pair<unsigned int, unsigned int>
    edge_key(const unsigned int a, const unsigned int b)
    {
      return a < b ? std::make_pair(a, b) : std::make_pair(b, a);
    }
  } // namespace detail


  MeshGroups
  read_gmsh(const std::string &msh_file, Triangulation<2, 3> &triangulation)
  {
    AssertThrow(triangulation.n_levels() == 0,
                ExcMessage("read_gmsh() needs an empty triangulation"));

    const RawMesh raw = load_with_gmsh(msh_file);
    try
      {
        return build_triangulation(msh_file, raw, triangulation);
      }
    catch (...)
      {
        // A .msh generated from a .geo that yields no usable mesh goes with the error.
        if (raw.generated)
          remove_generated_msh(msh_file);
        throw;
      }
  }


  MeshGroups
  detail::build_triangulation(const std::string   &msh_file,
                              const RawMesh       &raw,
                              Triangulation<2, 3> &triangulation)
  {
    if (raw.triangles.empty())
      throw InputError(msh_file, "", "the mesh has no triangles");

    // Vertices: the nodes of the triangles, numbered compactly in the order of their
    // tags.
    std::vector<std::size_t> vertex_node_tags;
    for (const RawTriangle &triangle : raw.triangles)
      vertex_node_tags.insert(vertex_node_tags.end(),
                              triangle.nodes.begin(),
                              triangle.nodes.end());
    std::sort(vertex_node_tags.begin(), vertex_node_tags.end());
    vertex_node_tags.erase(std::unique(vertex_node_tags.begin(), vertex_node_tags.end()),
                           vertex_node_tags.end());

    const unsigned int                            n_vertices = vertex_node_tags.size();
    std::unordered_map<std::size_t, unsigned int> vertex_of_node;
    std::vector<Point<3>>                         vertices(n_vertices);
    for (unsigned int v = 0; v < n_vertices; ++v)
      {
        const auto coordinates = raw.node_coordinates.find(vertex_node_tags[v]);
        if (coordinates == raw.node_coordinates.end())
          throw InputError(msh_file,
                           "",
                           "node " + std::to_string(vertex_node_tags[v]) +
                             " is used by a triangle but not defined");
        vertex_of_node[vertex_node_tags[v]] = v;
        vertices[v]                         = coordinates->second;
      }

    // Cells, with checks for repeated and degenerate triangles.
    const unsigned int                                  n_cells = raw.triangles.size();
    std::vector<CellData<2>>                            cells(n_cells, CellData<2>(3));
    std::map<std::array<unsigned int, 3>, unsigned int> cell_of_vertex_set;
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        const RawTriangle &triangle = raw.triangles[c];
        const std::string  name     = "triangle " + std::to_string(triangle.tag);
        for (unsigned int i = 0; i < 3; ++i)
          cells[c].vertices[i] = vertex_of_node.at(triangle.nodes[i]);

        std::array<unsigned int, 3> sorted{
          {cells[c].vertices[0], cells[c].vertices[1], cells[c].vertices[2]}};
        std::sort(sorted.begin(), sorted.end());
        if (sorted[0] == sorted[1] || sorted[1] == sorted[2])
          throw InputError(msh_file,
                           "",
                           "degenerate (zero-area) " + name +
                             ": it uses the same node twice");

        if (const auto degenerate = degenerate_triangle(vertices[cells[c].vertices[0]],
                                                        vertices[cells[c].vertices[1]],
                                                        vertices[cells[c].vertices[2]]))
          throw InputError(msh_file,
                           "",
                           "degenerate (zero-area) " + name + ": " + *degenerate);

        const auto [other, inserted] = cell_of_vertex_set.emplace(sorted, c);
        if (!inserted)
          throw InputError(msh_file,
                           "",
                           "triangles " +
                             std::to_string(raw.triangles[other->second].tag) + " and " +
                             std::to_string(triangle.tag) + " have the same three nodes");
      }

    // Edges (sorted vertex pairs) with the cells using them and in which direction: in a
    // manifold, consistently oriented surface an interior edge goes once each way.
    Edges edges;
    for (unsigned int c = 0; c < n_cells; ++c)
      for (unsigned int i = 0; i < 3; ++i)
        {
          const unsigned int a = cells[c].vertices[i];
          const unsigned int b = cells[c].vertices[(i + 1) % 3];
          edges[edge_key(a, b)].push_back({c, a < b});
        }
    for (const auto &[edge, uses] : edges)
      {
        const std::string edge_name =
          edge_text(vertex_node_tags[edge.first], vertex_node_tags[edge.second]);
        if (uses.size() > 2)
          {
            std::string tags;
            for (const EdgeUse &use : uses)
              tags +=
                (tags.empty() ? "" : ", ") + std::to_string(raw.triangles[use.cell].tag);
            throw InputError(msh_file,
                             "",
                             "non-manifold edge " + edge_name + ": shared by " +
                               std::to_string(uses.size()) + " triangles (" + tags +
                               "), at most 2 allowed");
          }
        if (uses.size() == 2 && uses[0].ascending == uses[1].ascending)
          throw InputError(msh_file,
                           "",
                           "surface is not consistently oriented: triangles " +
                             std::to_string(raw.triangles[uses[0].cell].tag) + " and " +
                             std::to_string(raw.triangles[uses[1].cell].tag) +
                             " run through their common edge " + edge_name +
                             " in the same direction");
      }

    MeshGroups groups;

    const auto boundary_ids =
      add_line_groups(msh_file, raw, vertex_of_node, edges, groups);
    add_surface_groups(msh_file, raw, cells, groups);
    add_point_groups(msh_file, raw, vertex_of_node, vertices, groups);

    try
      {
        triangulation.create_triangulation(vertices, cells, SubCellData());
      }
    catch (const ExceptionBase &error)
      {
        triangulation.clear();
        std::ostringstream info;
        error.print_info(info);
        std::string text = info.str();
        text.erase(text.find_last_not_of(" \n\t") + 1);
        throw InputError(msh_file,
                         "",
                         "deal.II cannot build a triangulation from it: " + text);
      }

    // Boundary ids; faces not in a line group keep id 0.
    std::size_t n_marked_faces = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            const auto face = cell->face(f);
            const auto id =
              boundary_ids.find(edge_key(face->vertex_index(0), face->vertex_index(1)));
            if (id != boundary_ids.end())
              {
                face->set_boundary_id(id->second);
                ++n_marked_faces;
              }
          }
    AssertThrow(n_marked_faces == boundary_ids.size(), ExcInternalError());

    return groups;
  }
} // namespace clothsim::mesh
