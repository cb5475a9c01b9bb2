#pragma once

// A probe of the output: a named point of the reference surface, located in the triangle
// that contains it. Its displacement, written to probes.csv, is interpolated linearly in
// that triangle: u(p) = Σ_v w_v u_v with the barycentric weights w_v of p.

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>
#include <deal.II/lac/trilinos_vector.h>

#include <boost/serialization/array.hpp>
#include <boost/serialization/string.hpp>

#include <mpi.h>

#include <array>
#include <string>
#include <vector>

namespace clothsim
{
  using namespace dealii;

  struct ProbeLocation
  {
    std::string name;
    Point<3>    reference_point; // the surface point closest to the point given, m
    // The triangle's three vertices: their x, y, z displacement dofs and weights.
    std::array<std::array<types::global_dof_index, 3>, 3> vertex_dofs;
    std::array<double, 3>                                 weights;
    double distance = 0.; // from the point as given to the surface, m

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &name &reference_point &vertex_dofs &weights &distance;
    }
  };

  // Each probe's displacement in `u` (any parallel layout: each dof counted by the rank
  // that owns it), the same on every rank. Collective over `communicator`.
  std::vector<Tensor<1, 3>>
  probe_displacements(const std::vector<ProbeLocation>    &probes,
                      const TrilinosWrappers::MPI::Vector &u,
                      const MPI_Comm                       communicator);
} // namespace clothsim
