#include "io/probe_location.h"

namespace clothsim
{
  std::vector<Tensor<1, 3>>
  probe_displacements(const std::vector<ProbeLocation>    &probes,
                      const TrilinosWrappers::MPI::Vector &u,
                      const MPI_Comm                       communicator)
  {
    const IndexSet     &owned = u.locally_owned_elements();
    std::vector<double> values(3 * probes.size(), 0.);
    for (unsigned int p = 0; p < probes.size(); ++p)
      for (unsigned int v = 0; v < 3; ++v)
        for (unsigned int d = 0; d < 3; ++d)
          if (owned.is_element(probes[p].vertex_dofs[v][d]))
            values[3 * p + d] += probes[p].weights[v] * u(probes[p].vertex_dofs[v][d]);
    MPI_Allreduce(
      MPI_IN_PLACE, values.data(), values.size(), MPI_DOUBLE, MPI_SUM, communicator);
    std::vector<Tensor<1, 3>> displacements(probes.size());
    for (unsigned int p = 0; p < probes.size(); ++p)
      for (unsigned int d = 0; d < 3; ++d)
        displacements[p][d] = values[3 * p + d];
    return displacements;
  }
} // namespace clothsim
