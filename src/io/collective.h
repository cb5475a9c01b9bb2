#pragma once

// Errors that happen on some MPI ranks only (rank 0 reads the mesh, writes the CSVs, ...)
// must reach every rank, or the others wait forever in their next collective call.
// run_collectively runs an action on every rank and then agrees: if it threw on any rank,
// every rank throws the error of the lowest such rank, with its type (InputError,
// io::OutputError, std::bad_alloc; anything else as std::runtime_error) and message.
// on_all_ranks agrees on a condition: true on every rank if it holds on every rank.

#include <mpi.h>

#include <functional>

namespace clothsim::io
{
  // Collective over `communicator`: every rank must call it.
  void
  run_collectively(const MPI_Comm communicator, const std::function<void()> &action);

  // Whether `value` holds on every rank (collective).
  bool
  on_all_ranks(const bool value, const MPI_Comm communicator);
} // namespace clothsim::io
