// Running gnuplot for io/line_plot: a child process (posix_spawnp) in the plot's
// directory, its output into a log file, waited for.

#include "io/line_plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern char **environ;

namespace clothsim::io
{
  std::string
  run_gnuplot(const std::string              &directory,
              const std::vector<std::string> &arguments,
              const std::string              &log_file)
  {
    std::vector<std::string> words = {"gnuplot"};
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char *> argv;
    for (std::string &word : words)
      argv.push_back(word.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addchdir_np(&actions, directory.c_str());
    posix_spawn_file_actions_addopen(
      &actions, 1, log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    pid_t     child = 0;
    const int result =
      posix_spawnp(&child, "gnuplot", &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (result != 0) // no gnuplot ran: no log either
      std::remove(log_file.c_str());
    if (result == ENOENT)
      return "gnuplot not found on PATH (Debian package gnuplot-nox)";
    if (result != 0)
      return std::string("cannot start gnuplot: ") + std::strerror(result);

    int status = 0;
    while (waitpid(child, &status, 0) < 0)
      if (errno != EINTR)
        return std::string("waiting for gnuplot: ") + std::strerror(errno);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
      return "";

    std::ifstream log(log_file);
    std::string   text((std::istreambuf_iterator<char>(log)),
                     std::istreambuf_iterator<char>());
    if (text.size() > 400)
      text = text.substr(0, 400) + " ...";
    for (char &c : text)
      if (c == '\n')
        c = ' ';
    return (WIFEXITED(status)
              ? "gnuplot exited with status " + std::to_string(WEXITSTATUS(status))
              : "gnuplot died of signal " + std::to_string(WTERMSIG(status))) +
           (text.empty() ? std::string() : " (" + text + ")") + " (log: " + log_file +
           ")";
  }
} // namespace clothsim::io
