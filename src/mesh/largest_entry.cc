#include "mesh/largest_entry.h"

#include <deal.II/base/mpi.h>

#include <cmath>
#include <sstream>

namespace clothsim::mesh
{
  namespace
  {
    std::string
    coordinates(const Point<3> &x)
    {
      std::ostringstream text;
      text << '(' << x[0] << ", " << x[1] << ", " << x[2] << ')';
      return text.str();
    }

    // What owned dof `dof` is: a vertex's displacement component (from an element of
    // this rank, which owns the dof) or an edge's angle (from the edge table, whose end
    // points are in the same order on every rank).
    std::string
    describe(const Discretization         &discretization,
             const types::global_dof_index dof,
             const double                  value)
    {
      std::ostringstream text;
      text.precision(3);
      for (const Discretization::Element &element : discretization.elements())
        for (unsigned int k = 0; k < 9; ++k)
          if (element.dofs[k] == dof)
            {
              text << "the "
                   << "xyz"[k % 3] << " displacement of the vertex at "
                   << coordinates(element.reference[k / 3]) << " m, " << value << " m";
              return text.str();
            }
      for (const Discretization::Edge &edge : discretization.edges())
        if (edge.angle_dof == dof)
          {
            text << "the director angle of the edge from "
                 << coordinates(edge.reference_points[0]) << " to "
                 << coordinates(edge.reference_points[1]) << " m, " << value << " rad";
            return text.str();
          }
      text << "unknown " << dof << ", " << value;
      return text.str();
    }
  } // namespace


  std::string
  describe_largest_entry(const Discretization &discretization, const VectorType &vector)
  {
    const MPI_Comm          communicator = discretization.get_communicator();
    double                  largest      = 0.;
    types::global_dof_index at           = 0;
    for (const types::global_dof_index dof : discretization.owned_dofs())
      if (std::abs(vector[dof]) > largest)
        {
          largest = std::abs(vector[dof]);
          at      = dof;
        }
    const double overall = Utilities::MPI::max(largest, communicator);
    if (!(overall > 0.))
      return {};
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
    const unsigned int holder =
      Utilities::MPI::min(largest == overall
                            ? rank
                            : Utilities::MPI::n_mpi_processes(communicator),
                          communicator);
    const std::string text =
      rank == holder ? describe(discretization, at, vector[at]) : std::string();
    return Utilities::MPI::broadcast(communicator, text, holder);
  }
} // namespace clothsim::mesh
