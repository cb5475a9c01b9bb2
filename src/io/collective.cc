#include "io/collective.h"

#include <deal.II/base/mpi.h>

#include "io/input_error.h"
#include "io/output_file.h"

#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace clothsim::io
{
  namespace
  {
    // The error types that cross ranks, and what is sent for each.
    enum Kind : int
    {
      none,
      input,
      output,
      memory,
      other
    };
  } // namespace


  void
  run_collectively(const MPI_Comm communicator, const std::function<void()> &action)
  {
    Kind                     kind = none;
    std::vector<std::string> fields; // input: file, entry, message; others: message
    try
      {
        action();
      }
    catch (const InputError &error)
      {
        kind   = input;
        fields = {error.file, error.entry, error.message};
      }
    catch (const OutputError &error)
      {
        kind   = output;
        fields = {error.path, error.reason};
      }
    catch (const std::bad_alloc &)
      {
        kind = memory;
      }
    catch (const std::exception &error)
      {
        kind   = other;
        fields = {error.what()};
      }

    const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(communicator);
    const unsigned int rank    = dealii::Utilities::MPI::this_mpi_process(communicator);
    const unsigned int failing =
      dealii::Utilities::MPI::min(kind == none ? n_ranks : rank, communicator);
    if (failing == n_ranks)
      return;
    if (n_ranks > 1)
      {
        kind   = static_cast<Kind>(dealii::Utilities::MPI::broadcast(communicator,
                                                                   static_cast<int>(kind),
                                                                   failing));
        fields = dealii::Utilities::MPI::broadcast(communicator, fields, failing);
      }
    switch (kind)
      {
        case input:
          throw InputError(fields.at(0), fields.at(1), fields.at(2));
        case output:
          throw OutputError(fields.at(0), fields.at(1));
        case memory:
          throw std::bad_alloc();
        default:
          throw std::runtime_error(fields.at(0));
      }
  }


  bool
  on_all_ranks(const bool value, const MPI_Comm communicator)
  {
    int local = value ? 1 : 0, all = 0;
    MPI_Allreduce(&local, &all, 1, MPI_INT, MPI_MIN, communicator);
    return all == 1;
  }
} // namespace clothsim::io
