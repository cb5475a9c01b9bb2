#include "mesh/child_process.h"

#include "io/input_error.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <iostream>
#include <vector>

namespace clothsim::mesh
{
  namespace
  {
    // The child's report of an InputError: file, entry and message, each followed by a
    // NUL byte.
    std::string
    encode(const InputError &error)
    {
      return error.file + '\0' + error.entry + '\0' + error.message + '\0';
    }

    void
    write_all(const int descriptor, const std::string &text)
    {
      std::size_t done = 0;
      while (done < text.size())
        {
          const ssize_t written =
            ::write(descriptor, text.data() + done, text.size() - done);
          if (written < 0 && errno == EINTR)
            continue;
          if (written <= 0)
            return;
          done += static_cast<std::size_t>(written);
        }
    }

    std::string
    read_all(const int descriptor)
    {
      std::string text;
      char        buffer[4096];
      while (true)
        {
          const ssize_t n = ::read(descriptor, buffer, sizeof(buffer));
          if (n < 0 && errno == EINTR)
            continue;
          if (n <= 0)
            return text;
          text.append(buffer, static_cast<std::size_t>(n));
        }
    }
  } // namespace


  void
  run_in_child_process(const std::string           &file,
                       const std::string           &what,
                       const std::function<void()> &work)
  {
    int channel[2];
    if (::pipe(channel) != 0)
      throw InputError(file,
                       "",
                       "cannot start a process to read it: " +
                         std::string(std::strerror(errno)));
    // Nothing buffered may be written twice.
    std::cout.flush();
    std::cerr.flush();
    const pid_t child = ::fork();
    if (child < 0)
      {
        ::close(channel[0]);
        ::close(channel[1]);
        throw InputError(file,
                         "",
                         "cannot start a process to read it: " +
                           std::string(std::strerror(errno)));
      }
    if (child == 0)
      {
        // The child: no MPI, no destructors of the parent's objects (_exit). A crash
        // kills it at once: MPI's handlers of fatal signals, inherited from the parent,
        // print a backtrace, which can deadlock on a heap that the crash corrupted (seen:
        // gmsh's "double free or corruption" on a fuzzed .msh, then a hang).
        for (const int fatal : {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL})
          std::signal(fatal, SIG_DFL);
        // What the child has to say goes through the pipe; glibc's report of a corrupted
        // heap would come before the parent's one-line error.
        if (const int null = ::open("/dev/null", O_WRONLY); null >= 0)
          ::dup2(null, STDERR_FILENO);
        ::close(channel[0]);
        int status = 0;
        try
          {
            work();
          }
        catch (const InputError &error)
          {
            write_all(channel[1], encode(error));
            status = 1;
          }
        catch (...)
          {
            status = 2;
          }
        ::close(channel[1]);
        ::_exit(status);
      }

    ::close(channel[1]);
    const std::string report = read_all(channel[0]);
    ::close(channel[0]);
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR)
      {}
    if (WIFSIGNALED(status))
      throw InputError(file,
                       "",
                       what + " crashed (" + strsignal(WTERMSIG(status)) +
                         "): the file is malformed");
    if (WIFEXITED(status) && WEXITSTATUS(status) == 1)
      {
        std::vector<std::string> fields;
        std::size_t              start = 0;
        for (std::size_t end = report.find('\0'); end != std::string::npos;
             end             = report.find('\0', start = end + 1))
          fields.push_back(report.substr(start, end - start));
        if (fields.size() == 3)
          throw InputError(fields[0], fields[1], fields[2]);
      }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
      throw InputError(file, "", what + " failed without a message");
  }
} // namespace clothsim::mesh
