// The mesh of gmsh's current model as plain data: node coordinates, triangles, and the
// physical groups of points, lines and surfaces.

#include "mesh/gmsh_reader_detail.h"

#include "io/input_error.h"

#include <gmsh.h>

namespace clothsim::mesh::detail
{
  namespace
  {
    // gmsh element type of the 2-node line, the 3-node triangle.
    constexpr int gmsh_line_type     = 1;
    constexpr int gmsh_triangle_type = 2;


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
  } // namespace


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
          raw.triangles.push_back(
            {element_tags[k][e],
             {{node_tags[k][3 * e], node_tags[k][3 * e + 1], node_tags[k][3 * e + 2]}}});
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
            gmsh::model::mesh::getNodesForPhysicalGroup(0, tag, group.nodes, coordinates);
            raw.point_groups.push_back(std::move(group));
          }
        else if (dim == 1)
          {
            RawLineGroup     group{name, tag, {}};
            std::vector<int> curves;
            gmsh::model::getEntitiesForPhysicalGroup(1, tag, curves);
            for (const int curve : curves)
              {
                gmsh::model::mesh::getElements(types, element_tags, node_tags, 1, curve);
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
} // namespace clothsim::mesh::detail
