#include "time/interruption.h"

#include <deal.II/base/mpi.h>

#include <csignal>
#include <cstring>
#include <unistd.h>

namespace clothsim
{
  namespace
  {
    volatile std::sig_atomic_t arrived  = 0;
    volatile std::sig_atomic_t announce = 0;

    extern "C" void
    record_signal(const int signal)
    {
      arrived = signal;
      if (announce != 0)
        {
          // Only async-signal-safe calls here: write(2) of a fixed text.
          const char *text = signal == SIGINT ? "\nclothsim: SIGINT: stopping after the "
                                                "current step (again: stop at once)\n"
                                              : "\nclothsim: SIGTERM: stopping after the "
                                                "current step (again: stop at once)\n";
          const ssize_t ignored = ::write(STDOUT_FILENO, text, std::strlen(text));
          (void)ignored;
        }
    }
  } // namespace


  void
  install_interruption_handlers(const bool announce_arrival)
  {
    announce = announce_arrival ? 1 : 0;
    struct sigaction action;
    std::memset(&action, 0, sizeof(action));
    action.sa_handler = record_signal;
    sigemptyset(&action.sa_mask);
    // The handler runs once; the next signal gets the default action (ends the process).
    action.sa_flags = SA_RESETHAND | SA_RESTART;
    for (const int signal : {SIGINT, SIGTERM})
      sigaction(signal, &action, nullptr);
  }


  int
  received_signal(const MPI_Comm communicator)
  {
    return dealii::Utilities::MPI::max(static_cast<int>(arrived), communicator);
  }


  std::string
  signal_name(const int signal)
  {
    switch (signal)
      {
        case SIGINT:
          return "SIGINT";
        case SIGTERM:
          return "SIGTERM";
        default:
          return "signal " + std::to_string(signal);
      }
  }
} // namespace clothsim
