#include "mesh/memory_estimate.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

namespace clothsim::mesh
{
  namespace
  {
    // Peak resident memory per triangle, measured as GNU time's "Maximum resident set
    // size" of clothsim (Release, deal.II 9.4, Trilinos 13.2; End time = 0.05 s, Write
    // VTK = false) between refinement levels, which leaves out the process's own
    // footprint (about 210 MB at level 0, already taken when the estimate is made):
    //   params/hanging-sheet.prm (membrane, CG + AMG), one rank:
    //     level 0:   5,402 triangles,   219 MB     level 1:  21,608 triangles,   284 MB
    //     level 2:  86,432 triangles,   550 MB     level 3: 345,728 triangles, 1,598 MB
    //     -> 3.99, 4.10, 4.04 kB per added triangle
    //   params/drape.prm (shell bending, MUMPS), one rank:
    //     level 0:   2,744 triangles,   227 MB     level 1:  10,976 triangles,   325 MB
    //     level 2:  43,904 triangles,   761 MB
    //     -> 12.0, 13.2 kB per added triangle (the direct solver's fill-in grows a
    //        little faster than the triangles: finer shells need somewhat more)
    constexpr double membrane_bytes_per_triangle = 4.14e3;
    constexpr double shell_bytes_per_triangle    = 13.6e3;
    // The part that every rank holds in full under MPI (each rank refines the whole mesh
    // before keeping its part). params/hanging-sheet.prm on two ranks, largest rank: 404
    // MB at level 2, 1,017 MB at level 3, 2.36 kB per added triangle against 4.04 on one
    // rank: a + b = 4.04, a + b/2 = 2.36 gives a replicated a = 0.69 kB, 17 %.
    constexpr double replicated_fraction = 0.17;


    // A value in kB from /proc/meminfo ("MemAvailable:   22584716 kB"), or -1.
    double
    meminfo_bytes(const std::string &key)
    {
      std::ifstream in("/proc/meminfo");
      std::string   line;
      while (std::getline(in, line))
        if (line.compare(0, key.size() + 1, key + ":") == 0)
          {
            std::istringstream fields(line.substr(key.size() + 1));
            double             kilobytes = -1.;
            fields >> kilobytes;
            return kilobytes >= 0. ? 1024. * kilobytes : -1.;
          }
      return -1.;
    }

    // A byte count in a cgroup file ("max" or missing: none), or -1.
    double
    cgroup_bytes(const std::string &file)
    {
      std::ifstream in(file);
      double        bytes = -1.;
      if (!(in >> bytes))
        return -1.;
      return bytes;
    }
  } // namespace


  double
  bytes_per_triangle(const MeshSetup &setup)
  {
    return setup.directors ? shell_bytes_per_triangle : membrane_bytes_per_triangle;
  }


  double
  available_memory()
  {
    double available = meminfo_bytes("MemAvailable");
    if (available < 0.)
      available = double(::sysconf(_SC_AVPHYS_PAGES)) * double(::sysconf(_SC_PAGESIZE));
    // A container's memory limit (cgroup v2) can be far below the machine's.
    const double limit = cgroup_bytes("/sys/fs/cgroup/memory.max");
    const double used  = cgroup_bytes("/sys/fs/cgroup/memory.current");
    if (limit >= 0. && used >= 0.)
      available = std::min(available, std::max(0., limit - used));
    return available;
  }


  MemoryEstimate
  estimate_memory(const MPI_Comm      communicator,
                  const std::uint64_t n_cells,
                  const MeshSetup    &setup)
  {
    // The ranks on this node share its memory.
    MPI_Comm node;
    MPI_Comm_split_type(communicator, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    const unsigned int ranks_on_node = Utilities::MPI::n_mpi_processes(node);
    MPI_Comm_free(&node);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);

    // Bytes this node's ranks need for `refinements`.
    const double per_triangle = bytes_per_triangle(setup);
    const auto   node_bytes   = [&](const unsigned int refinements) {
      const double triangles = double(n_cells) * std::pow(4., double(refinements));
      const double per_rank =
        per_triangle * triangles *
        (replicated_fraction + (1. - replicated_fraction) / n_ranks);
      return ranks_on_node * per_rank;
    };

    MemoryEstimate estimate;
    estimate.n_cells            = n_cells;
    estimate.refinements        = setup.global_refinements;
    estimate.bytes_per_triangle = per_triangle;
    estimate.ranks_on_node      = Utilities::MPI::max(ranks_on_node, communicator);
    estimate.needed_bytes =
      Utilities::MPI::max(node_bytes(setup.global_refinements), communicator);
    estimate.available_bytes      = Utilities::MPI::min(available_memory(), communicator);
    estimate.refinements_that_fit = 0;
    while (estimate.refinements_that_fit < setup.global_refinements &&
           Utilities::MPI::max(node_bytes(estimate.refinements_that_fit + 1),
                               communicator) <= estimate.available_bytes)
      ++estimate.refinements_that_fit;
    return estimate;
  }


  std::string
  MemoryEstimate::shortage() const
  {
    std::ostringstream message;
    message << refinements << " refinements of " << n_cells << " triangles need about "
            << std::fixed << std::setprecision(1) << needed_bytes / 1e9 << " GB ("
            << std::setprecision(0) << bytes_per_triangle
            << " bytes per triangle) on a node of " << ranks_on_node
            << " rank(s), which has " << std::setprecision(1) << available_bytes / 1e9
            << " GB available; at most " << refinements_that_fit << " refinements fit";
    return message.str();
  }
} // namespace clothsim::mesh
