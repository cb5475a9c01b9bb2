#pragma once

// The cloth as a triangle surface, for contact by primitive pairs
// (physics/mesh_contact.h, physics/self_contact.h): this rank's triangles, their vertices
// (owned or ghost) with their dofs, local indices in ghosted vectors, reference positions
// and lumped masses, and the edges this rank counts (each edge of the mesh by exactly one
// rank).

#include "mesh/discretization.h"
#include "physics/term.h"

#include <array>
#include <vector>

namespace clothsim::physics
{
  struct ClothSurface
  {
    struct Vertex
    {
      std::array<types::global_dof_index, 3> dofs;
      std::array<int, 3>                     local;
      Point<3>                               reference;
      double                                 mass; // lumped, kg
      bool                                   owned;
    };

    ClothSurface() = default;
    // `lumped_masses`: owned, each dof's vertex mass (kg).
    ClothSurface(const mesh::Discretization &discretization,
                 const VectorType           &lumped_masses);

    // The position of vertex p at u (`u_local`: a ghosted vector's values), m.
    Point<3>
    position(const unsigned int p, const double *u_local) const
    {
      Point<3> x = vertices[p].reference;
      for (unsigned int c = 0; c < 3; ++c)
        x[c] += u_local[vertices[p].local[c]];
      return x;
    }

    // The part of a ghosted vector's values `step_local` at vertex p.
    Tensor<1, 3>
    part(const unsigned int p, const double *step_local) const
    {
      Tensor<1, 3> dx;
      for (unsigned int c = 0; c < 3; ++c)
        dx[c] = step_local[vertices[p].local[c]];
      return dx;
    }

    std::vector<Vertex>                      vertices;
    std::vector<std::array<unsigned int, 3>> triangles;   // this rank's, into vertices
    std::vector<std::array<unsigned int, 2>> edges;       // this rank counts them
    std::vector<double>                      edge_length; // at rest, m
  };
} // namespace clothsim::physics
