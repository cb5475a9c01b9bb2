#pragma once

// Locating the scene's probes (Output/Probes) on the reference surface: each point goes
// to the triangle closest to it, as that triangle's closest point and its barycentric
// weights (io/probe_location.h).

#include "io/parameters.h"
#include "io/probe_location.h"
#include "mesh/discretization.h"

#include <string>
#include <vector>

namespace clothsim
{
  // Each probe in the triangle of the (refined) reference surface closest to its point,
  // the same on every rank (ties to the lowest rank, then to the first triangle). A point
  // farther from the surface than `tolerance` (m) is an InputError naming
  // `parameter_file`. Collective.
  std::vector<ProbeLocation>
  locate_probes(const mesh::Discretization &discretization,
                const std::vector<Probe>   &probes,
                const double                tolerance,
                const std::string          &parameter_file);
} // namespace clothsim
