#include "physics/cloth_surface.h"

#include <map>

namespace clothsim::physics
{
  ClothSurface::ClothSurface(const mesh::Discretization &discretization,
                             const VectorType           &lumped_masses)
  {
    VectorType masses;
    discretization.initialize_ghosted(masses);
    masses = lumped_masses;
    std::map<types::global_dof_index, unsigned int> vertex_of_dof;
    for (const auto &element : discretization.elements())
      {
        std::array<unsigned int, 3> triangle;
        for (unsigned int v = 0; v < 3; ++v)
          {
            const auto [slot, inserted] =
              vertex_of_dof.emplace(element.dofs[3 * v], vertices.size());
            triangle[v] = slot->second;
            if (!inserted)
              continue;
            Vertex vertex;
            for (unsigned int c = 0; c < 3; ++c)
              {
                vertex.dofs[c]  = element.dofs[3 * v + c];
                vertex.local[c] = element.local_dofs[3 * v + c];
              }
            vertex.reference = element.reference[v];
            vertex.mass      = masses[element.dofs[3 * v]];
            vertex.owned = discretization.owned_dofs().is_element(element.dofs[3 * v]);
            vertices.push_back(vertex);
          }
        triangles.push_back(triangle);
        for (unsigned int v = 0; v < 3; ++v)
          if (element.counts_edge[v])
            {
              const unsigned int a = triangle[(v + 1) % 3], b = triangle[(v + 2) % 3];
              edges.push_back({{a, b}});
              edge_length.push_back(
                vertices[a].reference.distance(vertices[b].reference));
            }
      }
  }
} // namespace clothsim::physics
