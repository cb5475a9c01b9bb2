#include "io/output_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace clothsim::io
{
  namespace
  {
    // Writes all of [data, data + size) to the descriptor; false (errno set) on failure.
    bool
    write_all(const int descriptor, const char *data, std::size_t size)
    {
      while (size > 0)
        {
          const ssize_t written = ::write(descriptor, data, size);
          if (written < 0)
            {
              if (errno == EINTR)
                continue;
              return false;
            }
          data += written;
          size -= static_cast<std::size_t>(written);
        }
      return true;
    }
  } // namespace


  std::string
  system_reason()
  {
    return std::strerror(errno);
  }


  void
  write_file_atomically(const std::string                         &path,
                        const std::function<void(std::ostream &)> &write)
  {
    std::ostringstream buffer;
    write(buffer);
    const std::string text = buffer.str();

    const std::string partial = path + ".partial";
    const int descriptor = ::open(partial.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (descriptor < 0)
      throw OutputError(path, system_reason());
    const bool        written = write_all(descriptor, text.data(), text.size());
    const std::string reason  = written ? "" : system_reason();
    // close(2) reports delayed write errors (e.g. on network file systems).
    const bool closed = ::close(descriptor) == 0;
    if (!written || !closed || std::rename(partial.c_str(), path.c_str()) != 0)
      {
        const std::string why = !written ? reason : system_reason();
        ::unlink(partial.c_str());
        throw OutputError(path, why);
      }
  }


  RowFile::~RowFile()
  {
    if (descriptor >= 0)
      ::close(descriptor);
  }


  void
  RowFile::open(const std::string &path)
  {
    if (descriptor >= 0)
      ::close(descriptor);
    file_path  = path;
    length     = 0;
    descriptor = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND, 0644);
    if (descriptor < 0)
      throw OutputError(path, system_reason());
  }


  void
  RowFile::reopen_at(const std::string &path, const long long kept)
  {
    if (descriptor >= 0)
      ::close(descriptor);
    file_path  = path;
    length     = kept;
    descriptor = ::open(path.c_str(), O_WRONLY | O_APPEND);
    if (descriptor < 0)
      throw OutputError(path, system_reason());
    struct stat status;
    if (::fstat(descriptor, &status) != 0)
      throw OutputError(path, system_reason());
    if (status.st_size < kept)
      throw OutputError(path,
                        "shorter (" + std::to_string(status.st_size) +
                          " bytes) than at the checkpoint (" + std::to_string(kept) +
                          " bytes)");
    if (::ftruncate(descriptor, kept) != 0)
      throw OutputError(path, system_reason());
  }


  void
  RowFile::append(const std::string &text)
  {
    if (descriptor < 0)
      throw OutputError(file_path, "the file is not open");
    if (!write_all(descriptor, text.data(), text.size()))
      {
        const std::string reason = system_reason();
        // Keep the file a sequence of whole rows.
        if (::ftruncate(descriptor, length) != 0)
          {
            // Nothing more can be done; the reason of the write is what matters.
          }
        throw OutputError(file_path, reason);
      }
    length += static_cast<long long>(text.size());
  }
} // namespace clothsim::io
