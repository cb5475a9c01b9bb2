#include "solvers/near_null_space.h"

#include <deal.II/base/mpi.h>

#include <algorithm>

namespace clothsim
{
  NearNullSpace
  make_near_null_space(const std::vector<ReferenceTriangle> &triangles,
                       const IndexSet                       &owned_dofs,
                       const IndexSet                       &relevant_dofs,
                       const bool                            other_unknowns,
                       const MPI_Comm                        communicator)
  {
    Tensor<1, 3> moment, normal_sum;
    double       area = 0.;
    for (const ReferenceTriangle &triangle : triangles)
      {
        const auto &X = triangle.vertices;
        for (unsigned int v = 0; v < 3; ++v)
          moment += (triangle.area / 3.) * X[v];
        normal_sum += 0.5 * cross_product_3d(X[1] - X[0], X[2] - X[0]);
        area += triangle.area;
      }
    for (unsigned int d = 0; d < 3; ++d)
      {
        moment[d]     = Utilities::MPI::sum(moment[d], communicator);
        normal_sum[d] = Utilities::MPI::sum(normal_sum[d], communicator);
      }
    area                        = Utilities::MPI::sum(area, communicator);
    const Tensor<1, 3> centroid = moment / area;
    // A sheet that is far from planar has no single in-plane rotation.
    const bool         nearly_planar = normal_sum.norm() > 0.9 * area;
    const Tensor<1, 3> normal        = normal_sum / normal_sum.norm();

    const unsigned int               n_owned = owned_dofs.n_elements();
    std::vector<std::vector<double>> modes(nearly_planar ? 4 : 3,
                                           std::vector<double>(n_owned, 0.));
    for (const ReferenceTriangle &triangle : triangles)
      for (unsigned int v = 0; v < 3; ++v)
        {
          const Tensor<1, 3> rotation =
            cross_product_3d(normal, triangle.vertices[v] - centroid);
          for (unsigned int c = 0; c < 3; ++c)
            if (owned_dofs.is_element(triangle.dofs[3 * v + c]))
              {
                const unsigned int i =
                  owned_dofs.index_within_set(triangle.dofs[3 * v + c]);
                modes[c][i] = 1.;
                if (nearly_planar)
                  modes[3][i] = rotation[c];
              }
        }
    NearNullSpace space{modes, 3u, IndexSet(), IndexSet(), IndexSet(), {}, {}};
    {
      // Each owned unknown's vertex (its vertex's first dof) or edge.
      std::vector<
        std::pair<types::global_dof_index, std::array<types::global_dof_index, 2>>>
        on_mesh;
      for (const ReferenceTriangle &triangle : triangles)
        for (unsigned int v = 0; v < 3; ++v)
          {
            const types::global_dof_index vertex = triangle.dofs[3 * v];
            for (unsigned int c = 0; c < 3; ++c)
              if (owned_dofs.is_element(triangle.dofs[3 * v + c]))
                on_mesh.push_back({triangle.dofs[3 * v + c], {{vertex, vertex}}});
            if (other_unknowns && owned_dofs.is_element(triangle.angle_dofs[v]))
              on_mesh.push_back(
                {triangle.angle_dofs[v],
                 {{triangle.dofs[3 * ((v + 1) % 3)], triangle.dofs[3 * ((v + 2) % 3)]}}});
          }
      std::sort(on_mesh.begin(), on_mesh.end());
      on_mesh.erase(std::unique(on_mesh.begin(),
                                on_mesh.end(),
                                [](const auto &a, const auto &b) {
                                  return a.first == b.first;
                                }),
                    on_mesh.end());
      for (const auto &[dof, vertices] : on_mesh)
        {
          space.mesh_dofs.push_back(dof);
          space.mesh_vertices.push_back(vertices);
        }
    }
    if (other_unknowns)
      {
        // Displacements and other unknowns interleave: AMG gets the displacement block.
        std::vector<types::global_dof_index> dofs;
        for (const ReferenceTriangle &triangle : triangles)
          for (const types::global_dof_index dof : triangle.dofs)
            if (owned_dofs.is_element(dof))
              dofs.push_back(dof);
        std::sort(dofs.begin(), dofs.end());
        dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
        space.displacement_dofs = IndexSet(owned_dofs.size());
        space.displacement_dofs.add_indices(dofs.begin(), dofs.end());
        space.displacement_dofs.compress();
        space.owned_dofs    = owned_dofs;
        space.relevant_dofs = relevant_dofs;
      }
    return space;
  }
} // namespace clothsim
