#pragma once

// An error in what the user gave us (parameter file, mesh, command line). main() prints
// it as one line, "clothsim: error: <file>: <entry>: <message>", and exits non-zero.

#include <stdexcept>
#include <string>

namespace clothsim
{
  class InputError : public std::runtime_error
  {
  public:
    // file: the file at fault (parameter file, mesh); entry: the parameter, group or line
    // concerned (may be empty); message: what was expected.
    InputError(const std::string &file,
               const std::string &entry,
               const std::string &message)
      : std::runtime_error(compose(file, entry, message))
      , file(file)
      , entry(entry)
      , message(message)
    {}

    const std::string file;
    const std::string entry;
    const std::string message;

  private:
    static std::string
    compose(const std::string &file, const std::string &entry, const std::string &message)
    {
      std::string text = file.empty() ? std::string("<command line>") : file;
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
