#pragma once

// A rigid triangle surface (a mesh obstacle) in its body frame, with bounding-volume
// hierarchies of its vertices, edges and triangles for the broad phase of contact. Its
// contact is by pairs of primitives (physics/mesh_contact.h), from either side, so the
// surface need not be closed or oriented.

#include "physics/aabb_tree.h"

#include <array>
#include <vector>

namespace clothsim::physics
{
  struct ObstacleSurface
  {
    ObstacleSurface(std::vector<Point<3>>                    vertices_in,
                    std::vector<std::array<unsigned int, 3>> triangles_in,
                    std::vector<std::array<unsigned int, 2>> edges_in)
      : vertices(std::move(vertices_in))
      , triangles(std::move(triangles_in))
      , edges(std::move(edges_in))
    {
      bounds = Box::around(vertices);
      std::vector<Box> boxes;
      for (const Point<3> &v : vertices)
        boxes.push_back(Box{v, v});
      vertex_tree = AabbTree(boxes);
      boxes.clear();
      for (const auto &e : edges)
        boxes.push_back(
          Box::around(std::array<Point<3>, 2>{{vertices[e[0]], vertices[e[1]]}}));
      edge_tree = AabbTree(boxes);
      boxes.clear();
      for (const auto &t : triangles)
        boxes.push_back(Box::around(
          std::array<Point<3>, 3>{{vertices[t[0]], vertices[t[1]], vertices[t[2]]}}));
      triangle_tree = AabbTree(boxes);
    }

    std::vector<Point<3>>                    vertices; // m
    std::vector<std::array<unsigned int, 3>> triangles;
    std::vector<std::array<unsigned int, 2>> edges;
    AabbTree                                 vertex_tree, edge_tree, triangle_tree;
    Box                                      bounds; // around every vertex
  };
} // namespace clothsim::physics
