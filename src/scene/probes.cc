#include "scene/probes.h"

#include <deal.II/base/mpi.h>

#include <boost/serialization/utility.hpp>

#include "io/input_error.h"
#include "physics/pair_distance.h"

#include <algorithm>
#include <limits>
#include <sstream>

namespace clothsim
{
  std::vector<ProbeLocation>
  locate_probes(const mesh::Discretization &discretization,
                const std::vector<Probe>   &probes,
                const double                tolerance,
                const std::string          &parameter_file)
  {
    const MPI_Comm             communicator = discretization.get_communicator();
    const unsigned int         rank = Utilities::MPI::this_mpi_process(communicator);
    std::vector<ProbeLocation> located;
    for (const Probe &probe : probes)
      {
        // The closest point of each locally owned triangle: the point-triangle distance
        // of contact (physics/pair_distance.h), whose weights on the triangle are minus
        // the closest point's barycentric coordinates.
        double        best = std::numeric_limits<double>::max();
        ProbeLocation candidate{probe.name, Point<3>(), {}, {{0., 0., 0.}}, 0.};
        for (const mesh::Discretization::Element &element : discretization.elements())
          {
            const physics::PairPoints   x{{probe.reference_point,
                                           element.reference[0],
                                           element.reference[1],
                                           element.reference[2]}};
            const physics::DistanceType type =
              physics::distance_type(physics::PairKind::point_triangle, x);
            const double distance = std::sqrt(physics::squared_distance(type, x));
            if (distance < best)
              {
                const std::array<double, 4> w = physics::closest_point_weights(type, x);
                best                          = distance;
                candidate.distance            = distance;
                candidate.reference_point     = Point<3>();
                for (unsigned int v = 0; v < 3; ++v)
                  {
                    candidate.weights[v] = -w[1 + v];
                    candidate.reference_point += -w[1 + v] * element.reference[v];
                    for (unsigned int d = 0; d < 3; ++d)
                      candidate.vertex_dofs[v][d] = element.dofs[3 * v + d];
                  }
              }
          }
        const auto all =
          Utilities::MPI::all_gather(communicator, std::make_pair(best, rank));
        const auto winner = std::min_element(all.begin(), all.end())->second;
        located.push_back(Utilities::MPI::broadcast(communicator, candidate, winner));

        const ProbeLocation &found = located.back();
        if (!(found.distance <= tolerance))
          {
            std::ostringstream message;
            message << "probe '" << found.name << "' is " << found.distance
                    << " m from the surface (its closest point is ("
                    << found.reference_point[0] << ", " << found.reference_point[1]
                    << ", " << found.reference_point[2]
                    << ")), farther than 'Output/Probe tolerance' allows (" << tolerance
                    << " m): it must lie on the cloth's surface";
            throw InputError(parameter_file, "Output/Probes", message.str());
          }
      }
    return located;
  }
} // namespace clothsim
