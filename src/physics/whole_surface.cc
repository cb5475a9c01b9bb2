#include "physics/whole_surface.h"

#include <deal.II/base/mpi.h>

#include "mesh/ghosted_values.h"

#include <algorithm>
#include <map>
#include <tuple>

namespace clothsim::physics
{
  WholeSurface::WholeSurface(const mesh::Discretization &discretization,
                             const VectorType           &lumped_masses)
    : communicator(discretization.get_communicator())
  {
    const ClothSurface local(discretization, lumped_masses);
    const unsigned int this_rank = Utilities::MPI::this_mpi_process(communicator);

    // This rank's owned vertices by their first dof: 7 numbers each (3 dofs, exact in a
    // double below 2^53; the reference position; the mass), and its triangles by their
    // vertices' first dofs.
    std::vector<unsigned int> mine;
    for (unsigned int p = 0; p < local.vertices.size(); ++p)
      if (local.vertices[p].owned)
        mine.push_back(p);
    std::sort(mine.begin(), mine.end(), [&](const unsigned int a, const unsigned int b) {
      return local.vertices[a].dofs[0] < local.vertices[b].dofs[0];
    });
    std::vector<double> vertex_data, triangle_data;
    for (const unsigned int p : mine)
      {
        const ClothSurface::Vertex &vertex = local.vertices[p];
        for (unsigned int c = 0; c < 3; ++c)
          vertex_data.push_back(static_cast<double>(vertex.dofs[c]));
        for (unsigned int c = 0; c < 3; ++c)
          vertex_data.push_back(vertex.reference[c]);
        vertex_data.push_back(vertex.mass);
      }
    for (const auto &triangle : local.triangles)
      for (const unsigned int p : triangle)
        triangle_data.push_back(static_cast<double>(local.vertices[p].dofs[0]));
    const std::vector<std::vector<double>> all_vertices =
      Utilities::MPI::all_gather(communicator, vertex_data);
    const std::vector<std::vector<double>> all_triangles =
      Utilities::MPI::all_gather(communicator, triangle_data);

    // Vertices by first dof, the same order on every rank and for every rank count.
    std::vector<std::tuple<types::global_dof_index, unsigned int, unsigned int>> order;
    for (unsigned int rank = 0; rank < all_vertices.size(); ++rank)
      for (unsigned int i = 0; 7 * i < all_vertices[rank].size(); ++i)
        order.emplace_back(
          static_cast<types::global_dof_index>(all_vertices[rank][7 * i]), rank, i);
    std::sort(order.begin(), order.end());
    std::map<types::global_dof_index, unsigned int> vertex_of_dof;
    std::vector<std::vector<unsigned int>>          vertex_of_slot(all_vertices.size());
    for (unsigned int rank = 0; rank < all_vertices.size(); ++rank)
      vertex_of_slot[rank].resize(all_vertices[rank].size() / 7);
    for (const auto &[dof, rank, i] : order)
      {
        const double        *data = &all_vertices[rank][7 * i];
        ClothSurface::Vertex vertex;
        const unsigned int   p = whole.vertices.size();
        for (unsigned int c = 0; c < 3; ++c)
          {
            vertex.dofs[c]      = static_cast<types::global_dof_index>(data[c]);
            vertex.local[c]     = static_cast<int>(3 * p + c);
            vertex.reference[c] = data[3 + c];
          }
        vertex.mass  = data[6];
        vertex.owned = rank == this_rank;
        whole.vertices.push_back(vertex);
        vertex_of_dof[dof]      = p;
        vertex_of_slot[rank][i] = p;
      }

    // Triangles (each cell is owned by one rank) in the order of their vertices; edges
    // those of the triangles, each once, in order.
    for (const std::vector<double> &data : all_triangles)
      for (unsigned int t = 0; 3 * t < data.size(); ++t)
        {
          std::array<unsigned int, 3> triangle;
          for (unsigned int v = 0; v < 3; ++v)
            triangle[v] =
              vertex_of_dof.at(static_cast<types::global_dof_index>(data[3 * t + v]));
          whole.triangles.push_back(triangle);
        }
    std::sort(whole.triangles.begin(), whole.triangles.end());
    for (const auto &triangle : whole.triangles)
      for (unsigned int v = 0; v < 3; ++v)
        whole.edges.push_back({{std::min(triangle[v], triangle[(v + 1) % 3]),
                                std::max(triangle[v], triangle[(v + 1) % 3])}});
    std::sort(whole.edges.begin(), whole.edges.end());
    whole.edges.erase(std::unique(whole.edges.begin(), whole.edges.end()),
                      whole.edges.end());
    for (const auto &[a, b] : whole.edges)
      whole.edge_length.push_back(
        whole.vertices[a].reference.distance(whole.vertices[b].reference));

    // The ghosted-vector indices of the vertices this rank holds, and gather()'s plan.
    ghosted.assign(whole.vertices.size(), {{-1, -1, -1}});
    for (const ClothSurface::Vertex &vertex : local.vertices)
      ghosted[vertex_of_dof.at(vertex.dofs[0])] = vertex.local;
    n_relevant_dofs = discretization.relevant_dofs().n_elements();
    for (const unsigned int p : mine)
      sent.push_back(local.vertices[p].local);
    int offset = 0;
    for (unsigned int rank = 0; rank < all_vertices.size(); ++rank)
      {
        counts.push_back(3 * static_cast<int>(vertex_of_slot[rank].size()));
        offsets.push_back(offset);
        offset += counts.back();
        arriving.insert(arriving.end(),
                        vertex_of_slot[rank].begin(),
                        vertex_of_slot[rank].end());
      }
  }


  void
  WholeSurface::gather(const VectorType &u, std::vector<double> &all) const
  {
    const double *u_local = ghosted_values(u, n_relevant_dofs);
    send_buffer.resize(3 * sent.size());
    for (unsigned int i = 0; i < sent.size(); ++i)
      for (unsigned int c = 0; c < 3; ++c)
        send_buffer[3 * i + c] = u_local[sent[i][c]];
    receive_buffer.resize(3 * arriving.size());
    const int ierr = MPI_Allgatherv(send_buffer.data(),
                                    static_cast<int>(send_buffer.size()),
                                    MPI_DOUBLE,
                                    receive_buffer.data(),
                                    counts.data(),
                                    offsets.data(),
                                    MPI_DOUBLE,
                                    communicator);
    AssertThrowMPI(ierr);
    all.resize(3 * whole.vertices.size());
    for (unsigned int k = 0; k < arriving.size(); ++k)
      for (unsigned int c = 0; c < 3; ++c)
        all[3 * arriving[k] + c] = receive_buffer[3 * k + c];
  }
} // namespace clothsim::physics
