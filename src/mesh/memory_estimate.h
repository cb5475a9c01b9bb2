#pragma once

// How much memory a run will take, predicted before the mesh is refined: refinement
// quarters every triangle, so r refinements of a mesh of n cells give n 4^r triangles,
// and a run's memory grows in proportion to its triangles. A refinement level the node
// cannot hold is better refused up front than met by std::bad_alloc in the middle of
// refine_global().

#include <deal.II/base/mpi.h>

#include "mesh/discretization.h"

#include <cstdint>
#include <string>

namespace clothsim::mesh
{
  // Measured peak memory of a run per triangle, in bytes, beyond the process's own
  // footprint (libraries; see memory_estimate.cc for the measurements).
  double
  bytes_per_triangle(const MeshSetup &setup);

  // Memory this node can still give, in bytes: MemAvailable of /proc/meminfo, less any
  // cgroup limit's headroom; the free physical pages where /proc/meminfo is missing.
  double
  available_memory();

  struct MemoryEstimate
  {
    std::uint64_t n_cells;            // of the mesh as read
    unsigned int  refinements;        // asked for
    double        bytes_per_triangle; // the figure used
    double        needed_bytes;       // by the ranks of the busiest node together
    double        available_bytes;    // on the node with the least available
    unsigned int  ranks_on_node;      // ranks sharing that node's memory
    // The most refinements (at most the ones asked for) whose estimate fits.
    unsigned int refinements_that_fit;

    bool
    fits() const
    {
      return needed_bytes <= available_bytes;
    }

    // "r refinements of n triangles need about X GB (...), which has Y GB available;
    // at most k refinements fit", for the error message when it does not fit.
    std::string
    shortage() const;
  };

  // The estimate for refining a mesh of `n_cells` triangles `setup.global_refinements`
  // times, run on the ranks of `communicator`: each rank refines the whole mesh before
  // keeping its part, and the rest is shared out. The same on every rank. Collective.
  MemoryEstimate
  estimate_memory(const MPI_Comm      communicator,
                  const std::uint64_t n_cells,
                  const MeshSetup    &setup);
} // namespace clothsim::mesh
