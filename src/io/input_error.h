#pragma once

// An error in what the user gave us (parameter file, mesh, command line). main() prints
// it as one line, "clothsim: error: <file>[:<line>]: <entry>: <message>", and exits 1.

#include <stdexcept>
#include <string>

namespace clothsim
{
  class InputError : public std::runtime_error
  {
  public:
    // file: the file at fault (parameter file, mesh) or the command-line option;
    // entry: the parameter (Section/Name), group or item concerned (may be empty);
    // message: what was expected; line: the file's line (0: none), as "file:line".
    InputError(const std::string &file,
               const std::string &entry,
               const std::string &message,
               const unsigned int line = 0)
      : std::runtime_error(compose(file, entry, message, line))
      , file(file)
      , entry(entry)
      , message(message)
      , line(line)
    {}

    const std::string  file;
    const std::string  entry;
    const std::string  message;
    const unsigned int line;

  private:
    static std::string
    compose(const std::string &file,
            const std::string &entry,
            const std::string &message,
            const unsigned int line)
    {
      std::string text = file.empty() ? std::string("<command line>") : file;
      if (line > 0)
        text += ":" + std::to_string(line);
      if (!entry.empty())
        text += ": " + entry;
      text += ": " + message;
      // One line, whatever the message holds.
      for (char &c : text)
        if (c == '\n')
          c = ' ';
      return text;
    }
  };
} // namespace clothsim
