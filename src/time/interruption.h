#pragma once

// SIGINT and SIGTERM stop a run cleanly. The handler only records the signal (and says so
// on rank 0); the steppers ask after every step attempt, all ranks together, and when a
// signal has arrived on any rank they write the frame of the last accepted state and
// throw Interrupted, which ends the program with exit code 128 + the signal number (130
// for SIGINT, 143 for SIGTERM, as shells report a process killed by it). A second signal
// ends the process at once (its default action); files stay whole then too, as every
// output file is written whole (io/output_file.h).

#include <mpi.h>

#include <stdexcept>
#include <string>

namespace clothsim
{
  class Interrupted : public std::runtime_error
  {
  public:
    Interrupted(const int signal, const std::string &message)
      : std::runtime_error(message)
      , signal(signal)
    {}

    const int signal; // the signal number

    // The documented exit code of an interrupted run.
    int
    exit_code() const
    {
      return 128 + signal;
    }
  };

  // Installs the handlers of SIGINT and SIGTERM; `announce`: the handler writes one line
  // to stdout when the signal arrives (rank 0 only).
  void
  install_interruption_handlers(const bool announce);

  // The signal that arrived on any rank of `communicator` (0: none). Collective.
  int
  received_signal(const MPI_Comm communicator);

  // "SIGINT", "SIGTERM", or "signal N".
  std::string
  signal_name(const int signal);
} // namespace clothsim
