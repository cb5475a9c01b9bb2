#pragma once

// Names the largest entry of a vector of unknowns for a message: what it moves (a
// vertex's displacement component or an edge's director angle) and where (reference
// coordinates). A failed Newton solve reports it for its last update: a line search
// that stalls at a crease shows one director angle there (README, "Contact with
// obstacles").

#include "mesh/discretization.h"

#include <string>

namespace clothsim::mesh
{
  // `vector` in the owned layout. The same text on every rank (the largest |entry| over
  // all ranks; on a tie the lowest rank's); empty if every entry is zero. Collective.
  std::string
  describe_largest_entry(const Discretization &discretization, const VectorType &vector);
} // namespace clothsim::mesh
