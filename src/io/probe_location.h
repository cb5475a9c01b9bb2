#pragma once

// A probe of the output: a named point of the reference surface, snapped to the nearest
// mesh vertex, whose displacement goes into probes.csv.

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <boost/serialization/array.hpp>
#include <boost/serialization/string.hpp>

#include <array>
#include <string>

namespace clothsim
{
  using namespace dealii;

  struct ProbeLocation
  {
    std::string                            name;
    Point<3>                               reference_point; // the vertex, m
    std::array<types::global_dof_index, 3> dofs;            // x, y, z displacement dofs
    double distance = 0.; // from the point as given to the vertex, m

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &name &reference_point &dofs &distance;
    }
  };
} // namespace clothsim
