#include "mesh/gmsh_reader.h"

#include "io/input_error.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/grid/tria_description.h>

#include <gmsh.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <unordered_map>
#include <utility>

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


  namespace
  {
    // gmsh element type of the 2-node line, the 3-node triangle.
    constexpr int gmsh_line_type     = 1;
    constexpr int gmsh_triangle_type = 2;

    // A triangle is degenerate if area < degenerate_tolerance * (longest edge)^2.
    constexpr double degenerate_tolerance = 1e-12;


    // What we take from gmsh's model, as plain data: the checks run after gmsh is closed.
    struct RawTriangle
    {
      std::size_t                tag;
      std::array<std::size_t, 3> nodes;
    };

    struct RawLine
    {
      std::size_t                tag;
      std::array<std::size_t, 2> nodes;
    };

    struct RawLineGroup
    {
      std::string          name;
      int                  tag;
      std::vector<RawLine> lines;
    };

    struct RawPointGroup
    {
      std::string              name;
      std::vector<std::size_t> nodes;
    };

    struct RawSurfaceGroup
    {
      std::string              name;
      int                      tag;
      std::vector<std::size_t> triangles; // element tags
    };

    struct RawMesh
    {
      std::unordered_map<std::size_t, Point<3>> node_coordinates;
      std::vector<RawTriangle>                  triangles;
      std::vector<RawLineGroup>                 line_groups;
      std::vector<RawPointGroup>                point_groups;
      std::vector<RawSurfaceGroup>              surface_groups;
    };


    // gmsh::initialize() on construction, gmsh::finalize() on destruction (also
    // unwinding).
    class GmshSession
    {
    public:
      GmshSession()
      {
        gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
        try
          {
            gmsh::option::setNumber("General.Terminal", 0);
          }
        catch (...)
          {
            gmsh::finalize();
            throw;
          }
      }

      ~GmshSession()
      {
        try
          {
            gmsh::finalize();
          }
        catch (...)
          {}
      }

      GmshSession(const GmshSession &) = delete;
      GmshSession &
      operator=(const GmshSession &) = delete;
    };


    // Runs `f` (calls into gmsh) and turns what gmsh throws (std::string in gmsh 4.8,
    // std::exception in later versions) into an InputError with `context` in front.
    template <typename Function>
    void
    call_gmsh(const std::string &msh_file, const std::string &context, Function &&f)
    {
      try
        {
          f();
        }
      catch (const InputError &)
        {
          throw;
        }
      catch (const std::string &message)
        {
          throw InputError(msh_file, "", context + ": " + message);
        }
      catch (const char *message)
        {
          throw InputError(msh_file, "", context + ": " + message);
        }
      catch (const std::exception &error)
        {
          throw InputError(msh_file, "", context + ": " + error.what());
        }
    }


    // gmsh's name of an element type, e.g. "Quadrilateral 4".
    std::string
    element_type_name(const int type)
    {
      std::string         name;
      int                 dim, order, n_nodes, n_primary_nodes;
      std::vector<double> local_coordinates;
      try
        {
          gmsh::model::mesh::getElementProperties(
            type, name, dim, order, n_nodes, local_coordinates, n_primary_nodes);
        }
      catch (...)
        {
          name = "unknown element";
        }
      return "'" + name + "' (gmsh type " + std::to_string(type) + ")";
    }


    std::string
    physical_name(const int dim, const int tag)
    {
      std::string name;
      gmsh::model::getPhysicalName(dim, tag, name);
      return name.empty() ? std::to_string(tag) : name;
    }


    // gmsh's message log while it lives (the logger is stopped also when unwinding: a
    // logger left running would carry its messages over to later gmsh sessions).
    class GmshLog
    {
    public:
      GmshLog()
      {
        gmsh::logger::start();
        std::vector<std::string> log;
        gmsh::logger::get(log);
        n_old_lines = log.size();
      }

      ~GmshLog()
      {
        try
          {
            gmsh::logger::stop();
          }
        catch (...)
          {}
      }

      GmshLog(const GmshLog &) = delete;
      GmshLog &
      operator=(const GmshLog &) = delete;

      // Throws an InputError with the first error logged since construction, if any.
      void
      throw_first_error(const std::string &msh_file, const std::string &context) const
      {
        const std::string        prefix = "Error: ";
        std::vector<std::string> log;
        gmsh::logger::get(log);
        for (std::size_t i = n_old_lines; i < log.size(); ++i)
          if (log[i].compare(0, prefix.size(), prefix) == 0)
            throw InputError(msh_file, "", context + ": " + log[i].substr(prefix.size()));
      }

    private:
      std::size_t n_old_lines;
    };


    // Writes the .msh for `geo_file` next to it: to a temporary name first, then renamed,
    // so that a concurrent reader (another MPI rank) never sees a half-written file.
    void
    generate_msh(const std::string &msh_file, const std::filesystem::path &geo_file)
    {
      const std::string context = "generating it from " + geo_file.string() + " failed";
      std::filesystem::path partial_file = msh_file;
      partial_file.replace_filename(partial_file.stem().string() + ".partial-" +
                                    std::to_string(::getpid()) + ".msh");
      call_gmsh(msh_file, context, [&]() {
        // Errors reported through the log, not thrown: a .geo syntax error thrown out of
        // gmsh's parser leaves the parser broken for every later .geo in this process.
        {
          const GmshLog log;
          gmsh::option::setNumber("General.AbortOnError", 0);
          gmsh::open(geo_file.string());
          log.throw_first_error(msh_file, context);
          gmsh::model::mesh::generate(2);
          log.throw_first_error(msh_file, context);
          gmsh::option::setNumber("General.AbortOnError", 2);
        }

        // Save all elements, also when no physical group holds the surface.
        gmsh::option::setNumber("Mesh.SaveAll", 1);
        gmsh::option::setNumber("Mesh.Binary", 0);
        gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
        gmsh::write(partial_file.string());
        gmsh::clear();
      });

      std::error_code error;
      std::filesystem::rename(partial_file, msh_file, error);
      if (error)
        {
          std::filesystem::remove(partial_file, error);
          throw InputError(msh_file, "", context + ": cannot write the .msh file");
        }
    }


    // Reads the mesh of the current gmsh model.
    RawMesh
    read_model(const std::string &msh_file)
    {
      RawMesh raw;

      {
        std::vector<std::size_t> node_tags;
        std::vector<double>      coordinates, parametric_coordinates;
        gmsh::model::mesh::getNodes(
          node_tags, coordinates, parametric_coordinates, -1, -1, false, false);
        for (std::size_t i = 0; i < node_tags.size(); ++i)
          raw.node_coordinates.emplace(node_tags[i],
                                       Point<3>(coordinates[3 * i],
                                                coordinates[3 * i + 1],
                                                coordinates[3 * i + 2]));
      }

      std::vector<int>                      types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;

      gmsh::model::mesh::getElements(types, element_tags, node_tags, 3, -1);
      for (unsigned int k = 0; k < types.size(); ++k)
        if (!element_tags[k].empty())
          throw InputError(msh_file,
                           "",
                           "element " + std::to_string(element_tags[k][0]) + " is a " +
                             element_type_name(types[k]) +
                             ", a volume element; only a surface of 3-node triangles "
                             "(gmsh type 2) is supported");

      gmsh::model::mesh::getElements(types, element_tags, node_tags, 2, -1);
      for (unsigned int k = 0; k < types.size(); ++k)
        {
          if (element_tags[k].empty())
            continue;
          if (types[k] != gmsh_triangle_type)
            throw InputError(msh_file,
                             "",
                             "element " + std::to_string(element_tags[k][0]) + " is a " +
                               element_type_name(types[k]) +
                               "; only 3-node triangles (gmsh type 2) are supported");
          for (std::size_t e = 0; e < element_tags[k].size(); ++e)
            raw.triangles.push_back({element_tags[k][e],
                                     {{node_tags[k][3 * e],
                                       node_tags[k][3 * e + 1],
                                       node_tags[k][3 * e + 2]}}});
        }

      gmsh::vectorpair groups;
      gmsh::model::getPhysicalGroups(groups);
      for (const auto &[dim, tag] : groups)
        {
          const std::string name = physical_name(dim, tag);
          if (dim == 0)
            {
              RawPointGroup       group{name, {}};
              std::vector<double> coordinates;
              gmsh::model::mesh::getNodesForPhysicalGroup(0,
                                                          tag,
                                                          group.nodes,
                                                          coordinates);
              raw.point_groups.push_back(std::move(group));
            }
          else if (dim == 1)
            {
              RawLineGroup     group{name, tag, {}};
              std::vector<int> curves;
              gmsh::model::getEntitiesForPhysicalGroup(1, tag, curves);
              for (const int curve : curves)
                {
                  gmsh::model::mesh::getElements(
                    types, element_tags, node_tags, 1, curve);
                  for (unsigned int k = 0; k < types.size(); ++k)
                    {
                      if (element_tags[k].empty())
                        continue;
                      if (types[k] != gmsh_line_type)
                        throw InputError(msh_file,
                                         name,
                                         "element " + std::to_string(element_tags[k][0]) +
                                           " is a " + element_type_name(types[k]) +
                                           "; line groups must consist of 2-node lines "
                                           "(gmsh type 1)");
                      for (std::size_t e = 0; e < element_tags[k].size(); ++e)
                        group.lines.push_back(
                          {element_tags[k][e],
                           {{node_tags[k][2 * e], node_tags[k][2 * e + 1]}}});
                    }
                }
              raw.line_groups.push_back(std::move(group));
            }
          else if (dim == 2)
            {
              RawSurfaceGroup  group{name, tag, {}};
              std::vector<int> surfaces;
              gmsh::model::getEntitiesForPhysicalGroup(2, tag, surfaces);
              for (const int surface : surfaces)
                {
                  gmsh::model::mesh::getElements(
                    types, element_tags, node_tags, 2, surface);
                  // Element types other than triangles were rejected above.
                  for (unsigned int k = 0; k < types.size(); ++k)
                    if (types[k] == gmsh_triangle_type)
                      group.triangles.insert(group.triangles.end(),
                                             element_tags[k].begin(),
                                             element_tags[k].end());
                }
              raw.surface_groups.push_back(std::move(group));
            }
          // Volume groups are empty (no volume elements).
        }

      return raw;
    }


    RawMesh
    load_with_gmsh(const std::string &msh_file)
    {
      namespace fs = std::filesystem;

      const bool     have_msh = fs::exists(msh_file);
      const fs::path geo_file = fs::path(msh_file).replace_extension(".geo");
      if (!have_msh && !fs::exists(geo_file))
        throw InputError(msh_file,
                         "",
                         "mesh file not found (nor a .geo to generate it from)");
      if (have_msh && !fs::is_regular_file(msh_file))
        throw InputError(msh_file, "", "not a regular file");

      std::unique_ptr<GmshSession> session;
      call_gmsh(msh_file, "gmsh cannot start", [&]() {
        session = std::make_unique<GmshSession>();
      });

      if (!have_msh)
        generate_msh(msh_file, geo_file);

      RawMesh raw;
      call_gmsh(msh_file, "gmsh cannot read it", [&]() {
        gmsh::open(msh_file);
        raw = read_model(msh_file);
      });
      return raw;
    }


    std::string
    edge_text(const std::size_t node_0, const std::size_t node_1)
    {
      return "(nodes " + std::to_string(node_0) + "-" + std::to_string(node_1) + ")";
    }


    // An edge as the sorted pair of its vertex indices.
    std::pair<unsigned int, unsigned int>
    edge_key(const unsigned int a, const unsigned int b)
    {
      return a < b ? std::make_pair(a, b) : std::make_pair(b, a);
    }
  } // namespace


  MeshGroups
  read_gmsh(const std::string &msh_file, Triangulation<2, 3> &triangulation)
  {
    AssertThrow(triangulation.n_levels() == 0,
                ExcMessage("read_gmsh() needs an empty triangulation"));

    const RawMesh raw = load_with_gmsh(msh_file);
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

        const Point<3> &p0   = vertices[cells[c].vertices[0]];
        const Point<3> &p1   = vertices[cells[c].vertices[1]];
        const Point<3> &p2   = vertices[cells[c].vertices[2]];
        const double    area = 0.5 * cross_product_3d(p1 - p0, p2 - p0).norm();
        const double    longest_edge_square = std::max(
          {(p1 - p0).norm_square(), (p2 - p1).norm_square(), (p0 - p2).norm_square()});
        if (!(area > degenerate_tolerance * longest_edge_square))
          {
            std::ostringstream message;
            message << "degenerate (zero-area) " << name << ": area " << area
                    << " for a longest edge of " << std::sqrt(longest_edge_square);
            throw InputError(msh_file, "", message.str());
          }

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
    struct EdgeUse
    {
      unsigned int cell;
      bool         ascending;
    };
    std::map<std::pair<unsigned int, unsigned int>, std::vector<EdgeUse>> edges;
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

    // Line groups: boundary id = physical tag, on boundary edges only.
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

    // Surface groups: material id = physical tag, on the triangles they hold.
    {
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

    // Point groups: coordinates of their nodes, which must be vertices of the triangles.
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
