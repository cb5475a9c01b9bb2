#include "io/checkpoint.h"

#include <deal.II/base/mpi.h>

#include "io/collective.h"
#include "io/input_error.h"
#include "io/output_file.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

namespace clothsim::io
{
  namespace
  {
    const std::string magic = "clothsim checkpoint 1\n";

    // FNV-1a, 64 bits: enough to tell a damaged file from a whole one.
    std::uint64_t
    hash_bytes(const std::string &bytes, std::uint64_t hash = 14695981039346656037ull)
    {
      for (const unsigned char c : bytes)
        {
          hash ^= c;
          hash *= 1099511628211ull;
        }
      return hash;
    }

    void
    put_word(std::string &out, const std::uint64_t word)
    {
      for (unsigned int b = 0; b < 8; ++b)
        out.push_back(static_cast<char>((word >> (8 * b)) & 0xff));
    }

    // Reads words and byte runs from a string; `ok` turns false past its end.
    class Reader
    {
    public:
      explicit Reader(const std::string &bytes)
        : bytes(bytes)
      {}

      std::uint64_t
      word()
      {
        if (position + 8 > bytes.size())
          {
            ok = false;
            return 0;
          }
        std::uint64_t result = 0;
        for (unsigned int b = 0; b < 8; ++b)
          result |=
            static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[position + b]))
            << (8 * b);
        position += 8;
        return result;
      }

      std::string
      run(const std::uint64_t length)
      {
        if (length > bytes.size() - position)
          {
            ok = false;
            return "";
          }
        std::string result = bytes.substr(position, length);
        position += length;
        return result;
      }

      bool
      at_end() const
      {
        return position == bytes.size();
      }

      bool ok = true;

    private:
      const std::string &bytes;
      std::size_t        position = 0;
    };
  } // namespace


  const std::vector<double> &
  CheckpointData::get(const std::string &name, const long long size) const
  {
    const auto found = numbers.find(name);
    if (found == numbers.end())
      throw InputError(source, "", "the checkpoint has no record '" + name + "'");
    if (size >= 0 && found->second.size() != static_cast<std::size_t>(size))
      throw InputError(source,
                       "",
                       "the checkpoint's record '" + name + "' has " +
                         std::to_string(found->second.size()) + " values, expected " +
                         std::to_string(size) +
                         " (written by another version of clothsim, or for another "
                         "mesh or partition)");
    return found->second;
  }


  const std::string &
  CheckpointData::get_text(const std::string &name) const
  {
    const auto found = texts.find(name);
    if (found == texts.end())
      throw InputError(source, "", "the checkpoint has no record '" + name + "'");
    return found->second;
  }


  std::string
  CheckpointData::serialize() const
  {
    std::string out;
    put_word(out, numbers.size() + texts.size());
    for (const auto &[name, values] : numbers)
      {
        put_word(out, name.size());
        out += name;
        put_word(out, 0);
        put_word(out, values.size());
        const std::size_t start = out.size();
        out.resize(start + 8 * values.size());
        for (std::size_t i = 0; i < values.size(); ++i)
          {
            std::uint64_t bits;
            std::memcpy(&bits, &values[i], 8);
            for (unsigned int b = 0; b < 8; ++b)
              out[start + 8 * i + b] = static_cast<char>((bits >> (8 * b)) & 0xff);
          }
      }
    for (const auto &[name, text] : texts)
      {
        put_word(out, name.size());
        out += name;
        put_word(out, 1);
        put_word(out, text.size());
        out += text;
      }
    return out;
  }


  CheckpointData
  CheckpointData::deserialize(const std::string &bytes, const std::string &source)
  {
    CheckpointData data;
    data.source = source;
    Reader              reader(bytes);
    const std::uint64_t count = reader.word();
    for (std::uint64_t k = 0; k < count && reader.ok; ++k)
      {
        const std::string   name   = reader.run(reader.word());
        const std::uint64_t kind   = reader.word();
        const std::uint64_t length = reader.word();
        if (kind == 0 && length <= bytes.size() / 8)
          {
            std::vector<double> values(length);
            for (double &value : values)
              {
                const std::uint64_t bits = reader.word();
                std::memcpy(&value, &bits, 8);
              }
            data.numbers[name] = std::move(values);
          }
        else if (kind == 1)
          data.texts[name] = reader.run(length);
        else
          reader.ok = false;
      }
    if (!reader.ok || !reader.at_end())
      throw InputError(source, "", "the checkpoint is malformed");
    return data;
  }


  std::string
  checkpoint_path(const std::string &directory)
  {
    return directory + "/checkpoint.bin";
  }


  unsigned long long
  write_checkpoint(const std::string    &directory,
                   const MPI_Comm        communicator,
                   const CheckpointData &run,
                   const CheckpointData &rank)
  {
    const bool is_root = dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
    // Each rank's section to rank 0, as raw bytes (deal.II's gather would pack and
    // compress them: measured 0.1 s for the 2.3 MB of the swinging sheet at N = 81).
    const std::string own     = rank.serialize();
    const int         n_ranks = dealii::Utilities::MPI::n_mpi_processes(communicator);
    std::vector<std::string> sections(is_root ? n_ranks : 0);
    if (n_ranks == 1)
      sections[0] = own;
    else
      {
        const int        length = static_cast<int>(own.size());
        std::vector<int> lengths(is_root ? n_ranks : 0), offsets(lengths.size(), 0);
        MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, communicator);
        std::string all;
        if (is_root)
          {
            for (int r = 1; r < n_ranks; ++r)
              offsets[r] = offsets[r - 1] + lengths[r - 1];
            all.resize(offsets.back() + lengths.back());
          }
        MPI_Gatherv(own.data(),
                    length,
                    MPI_CHAR,
                    all.data(),
                    lengths.data(),
                    offsets.data(),
                    MPI_CHAR,
                    0,
                    communicator);
        for (int r = 0; r < static_cast<int>(sections.size()); ++r)
          sections[r] = all.substr(offsets[r], lengths[r]);
      }
    unsigned long long size = 0;
    run_collectively(communicator, [&]() {
      if (!is_root)
        return;
      const std::string run_section = run.serialize();
      std::uint64_t     hash        = hash_bytes(run_section);
      for (const std::string &section : sections)
        hash = hash_bytes(section, hash);
      std::string header = magic;
      put_word(header, sections.size());
      put_word(header, run_section.size());
      for (const std::string &section : sections)
        put_word(header, section.size());
      put_word(header, hash);
      write_file_atomically(checkpoint_path(directory), [&](std::ostream &out) {
        out << header << run_section;
        for (const std::string &section : sections)
          out << section;
      });
      size = header.size() + run_section.size();
      for (const std::string &section : sections)
        size += section.size();
    });
    return size;
  }


  std::pair<CheckpointData, CheckpointData>
  read_checkpoint(const std::string &directory, const MPI_Comm communicator)
  {
    const bool is_root = dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
    const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(communicator);
    const std::string  path    = checkpoint_path(directory);
    std::string        run_section;
    std::vector<std::string> sections;
    run_collectively(communicator, [&]() {
      if (!is_root)
        return;
      std::ifstream in(path, std::ios::binary);
      if (!in)
        throw InputError(path,
                         "",
                         "no checkpoint to restart from (a run writes one with "
                         "'Output/Checkpoint interval' > 0, or when it is interrupted)");
      std::ostringstream buffer;
      buffer << in.rdbuf();
      const std::string bytes = buffer.str();
      if (bytes.compare(0, magic.size(), magic) != 0)
        throw InputError(path, "", "not a clothsim checkpoint");
      const std::string   body = bytes.substr(magic.size());
      Reader              reader(body);
      const std::uint64_t written_ranks = reader.word();
      if (reader.ok && written_ranks != n_ranks)
        throw InputError(path,
                         "",
                         "the checkpoint was written by " +
                           std::to_string(written_ranks) +
                           " MPI rank(s); restart it on as many (mpirun -np " +
                           std::to_string(written_ranks) + "), not " +
                           std::to_string(n_ranks));
      const std::uint64_t        run_size = reader.word();
      std::vector<std::uint64_t> sizes(n_ranks);
      for (std::uint64_t &size : sizes)
        size = reader.word();
      const std::uint64_t hash = reader.word();
      run_section              = reader.run(run_size);
      std::uint64_t computed   = hash_bytes(run_section);
      for (const std::uint64_t size : sizes)
        {
          sections.push_back(reader.run(size));
          computed = hash_bytes(sections.back(), computed);
        }
      if (!reader.ok || !reader.at_end())
        throw InputError(path, "", "the checkpoint is truncated or has extra bytes");
      if (computed != hash)
        throw InputError(path, "", "the checkpoint is corrupt (its checksum differs)");
    });
    if (n_ranks > 1)
      run_section = dealii::Utilities::MPI::broadcast(communicator, run_section, 0);
    // Each rank's section from rank 0.
    std::string own;
    if (n_ranks == 1)
      own = sections.at(0);
    else
      {
        if (is_root)
          {
            own = sections[0];
            for (unsigned int r = 1; r < n_ranks; ++r)
              {
                const unsigned long long length = sections[r].size();
                MPI_Send(&length, 1, MPI_UNSIGNED_LONG_LONG, r, 0, communicator);
                MPI_Send(sections[r].data(),
                         static_cast<int>(length),
                         MPI_CHAR,
                         r,
                         1,
                         communicator);
              }
          }
        else
          {
            unsigned long long length = 0;
            MPI_Recv(
              &length, 1, MPI_UNSIGNED_LONG_LONG, 0, 0, communicator, MPI_STATUS_IGNORE);
            own.resize(length);
            MPI_Recv(own.data(),
                     static_cast<int>(length),
                     MPI_CHAR,
                     0,
                     1,
                     communicator,
                     MPI_STATUS_IGNORE);
          }
      }
    std::pair<CheckpointData, CheckpointData> result;
    run_collectively(communicator, [&]() {
      result.first  = CheckpointData::deserialize(run_section, path);
      result.second = CheckpointData::deserialize(own, path);
    });
    return result;
  }
} // namespace clothsim::io
