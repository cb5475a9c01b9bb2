#pragma once

// The whole cloth surface on every MPI rank, for contact between primitives that lie on
// different ranks (physics/self_contact.h). Built once: every rank's owned vertices
// (reference position, lumped mass, dofs) and triangles are gathered, vertices ordered by
// their first dof and triangles by their vertices, so that every rank (and every rank
// count) holds the same surface in the same order. Edges are those of the triangles,
// each once. At each evaluation gather() copies all vertices' displacements from their
// owners (one all-gather of 3 values per vertex): a ghost layer that is the whole mesh.
// Its cost grows with the mesh, not with the contact; memory and traffic are 3 doubles
// per vertex and rank.

#include "mesh/discretization.h"
#include "physics/cloth_surface.h"

#include <array>
#include <vector>

namespace clothsim::physics
{
  class WholeSurface
  {
  public:
    // `lumped_masses`: owned, each dof's vertex mass (kg).
    WholeSurface(const mesh::Discretization &discretization,
                 const VectorType           &lumped_masses);

    // Every vertex, triangle and edge of the mesh. A vertex's `local` indexes the
    // array gather() fills (3 p + c); `owned` says whether this rank owns it.
    const ClothSurface &
    surface() const
    {
      return whole;
    }

    // All vertices' displacements at u (ghosted), 3 per vertex in surface()'s order.
    void
    gather(const VectorType &u, std::vector<double> &all) const;

    // The local index in a ghosted vector of vertex p's components (only for vertices
    // this rank holds; -1 otherwise).
    const std::array<int, 3> &
    ghosted_local(const unsigned int p) const
    {
      return ghosted[p];
    }

    MPI_Comm
    get_communicator() const
    {
      return communicator;
    }

  private:
    const MPI_Comm                  communicator;
    ClothSurface                    whole;
    std::vector<std::array<int, 3>> ghosted;
    // gather(): this rank's owned vertices in the order it sends them,
    // and every rank's sent vertices in the order they arrive, with their counts.
    unsigned int                    n_relevant_dofs = 0;
    std::vector<std::array<int, 3>> sent; // ghosted-vector indices
    std::vector<unsigned int>       arriving;
    std::vector<int>                counts, offsets;
    mutable std::vector<double>     send_buffer, receive_buffer;
  };
} // namespace clothsim::physics
