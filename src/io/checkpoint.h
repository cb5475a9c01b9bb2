#pragma once

// The checkpoint file of a run, `checkpoint.bin` in its output directory: the state a
// restart needs to continue bit-identically (io knows no model: it stores named records
// that the steppers and the model fill in). One section is the run's (written by rank
// 0: step controller, output counters, parameters), one section per MPI rank holds that
// rank's part (owned vector entries, the bending term's director references). Binary
// doubles are stored bit for bit.
//
// Layout: the line "clothsim checkpoint 1\n", then little-endian 64-bit words: the
// number of ranks, the byte length of the run's section and of each rank's section, an
// FNV-1a hash of all sections, then the sections. A section is a count followed by
// records: name length, name, kind (0 numbers, 1 text), length, data.
//
// The file is written atomically (io/output_file.h: under checkpoint.bin.partial, then
// renamed), so a crash, a kill or a full disk while writing leaves the previous
// checkpoint intact.

#include <mpi.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace clothsim::io
{
  // Named records of numbers (bit-exact doubles; counts up to 2^53 are exact) and texts.
  class CheckpointData
  {
  public:
    void
    set(const std::string &name, const std::vector<double> &values)
    {
      numbers[name] = values;
    }
    void
    set(const std::string &name, const double value)
    {
      numbers[name] = {value};
    }
    void
    set_text(const std::string &name, const std::string &text)
    {
      texts[name] = text;
    }

    bool
    has(const std::string &name) const
    {
      return numbers.count(name) > 0 || texts.count(name) > 0;
    }

    // The record `name`; a missing record (or a text where numbers are expected, or
    // numbers of another length than `size` if given) throws InputError naming the
    // checkpoint (set_source).
    const std::vector<double> &
    get(const std::string &name, const long long size = -1) const;
    double
    get_number(const std::string &name) const
    {
      return get(name, 1)[0];
    }
    const std::string &
    get_text(const std::string &name) const;

    // The bytes of the section, and the section from them (InputError naming `source`
    // if malformed).
    std::string
    serialize() const;
    static CheckpointData
    deserialize(const std::string &bytes, const std::string &source);

    // The file named in errors about missing records.
    void
    set_source(const std::string &file)
    {
      source = file;
    }
    const std::string &
    get_source() const
    {
      return source;
    }

  private:
    std::string                                source;
    std::map<std::string, std::vector<double>> numbers;
    std::map<std::string, std::string>         texts;
  };

  // The checkpoint's file name in an output directory.
  std::string
  checkpoint_path(const std::string &directory);

  // Writes the checkpoint: `run` from rank 0 (ignored elsewhere), `rank` from every rank.
  // Collective; a failed write throws OutputError on every rank and leaves the previous
  // checkpoint in place. Returns the file's size in bytes.
  unsigned long long
  write_checkpoint(const std::string    &directory,
                   const MPI_Comm        communicator,
                   const CheckpointData &run,
                   const CheckpointData &rank);

  // Reads the checkpoint in `directory`: the run's section (on every rank) and this
  // rank's. Collective; throws InputError (naming the file) on every rank if the file is
  // missing, truncated, corrupt or was written by another number of ranks.
  std::pair<CheckpointData, CheckpointData>
  read_checkpoint(const std::string &directory, const MPI_Comm communicator);
} // namespace clothsim::io
