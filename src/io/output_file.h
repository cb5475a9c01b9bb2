#pragma once

// Output files that are complete or absent, never truncated: a crash, a kill or a full
// disk at any moment leaves only whole files and whole rows.
//  - write_file_atomically: the file is written under a temporary name beside it
//    (`path`.partial), checked, and renamed onto `path` (rename(2) is atomic within a
//    file system), so readers see the old file or the new one.
//  - RowFile: an append-only text file (CSV) whose rows are written whole, each with one
//    write(2) loop; a failed write is cut back to the last complete row.
// Every failure throws OutputError with the file and the system's reason.

#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>

namespace clothsim::io
{
  // A file of the run's output could not be written (disk full, permissions, ...).
  class OutputError : public std::runtime_error
  {
  public:
    OutputError(const std::string &path, const std::string &reason)
      : std::runtime_error("cannot write " + path + ": " + reason)
      , path(path)
      , reason(reason)
    {}

    const std::string path;   // the file
    const std::string reason; // what went wrong, e.g. "No space left on device"
  };

  // Writes `path` whole or not at all: `write` fills a stream whose bytes go to
  // `path`.partial, which is then renamed onto `path`. On failure the partial file is
  // removed and OutputError is thrown.
  void
  write_file_atomically(const std::string                         &path,
                        const std::function<void(std::ostream &)> &write);

  // An append-only file of text rows (created or emptied by open()).
  class RowFile
  {
  public:
    RowFile() = default;
    ~RowFile();
    RowFile(const RowFile &) = delete;
    RowFile &
    operator=(const RowFile &) = delete;

    void
    open(const std::string &path);

    // Opens an existing file to append after its first `length` bytes (a restart: the
    // rows an interrupted run wrote after its checkpoint are cut off). OutputError if
    // the file is shorter.
    void
    reopen_at(const std::string &path, const long long length);

    // Bytes of complete rows written.
    long long
    size() const
    {
      return length;
    }

    // Appends `text` (one or more whole rows) with one write; on failure the file is cut
    // back to its previous length and OutputError is thrown.
    void
    append(const std::string &text);

    const std::string &
    path() const
    {
      return file_path;
    }

  private:
    std::string file_path;
    int         descriptor = -1;
    long long   length     = 0; // bytes of complete rows
  };

  // The system's reason for the last failed call (strerror(errno)).
  std::string
  system_reason();
} // namespace clothsim::io
