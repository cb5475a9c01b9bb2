#pragma once

// Helpers shared by the parameter sections (io/parameters*.cc); not part of the
// interface.

#include "io/parameters.h"

#include <string>

namespace clothsim::detail
{
  // 'x, y, z' as a vector (the entry's pattern has checked the three numbers).
  Tensor<1, 3>
  vector_entry(const std::string &text);
} // namespace clothsim::detail
