#pragma once

// Looking at an input file (parameter file, mesh) without std::filesystem's exceptions:
// a symbolic link loop or a name too long is bad input, reported as an InputError, not
// an uncaught std::filesystem::filesystem_error.

#include "io/input_error.h"

#include <cctype>
#include <filesystem>
#include <string>
#include <system_error>

namespace clothsim
{
  // The type of `file`, file_type::not_found if it (or a directory on its path) does not
  // exist. Any other failure to look at it (too many levels of symbolic links, file name
  // too long, permission denied) throws an InputError naming `file` and `entry` and
  // saying what went wrong.
  inline std::filesystem::file_type
  input_file_type(const std::string &file, const std::string &entry = "")
  {
    std::error_code                    error;
    const std::filesystem::file_status status = std::filesystem::status(file, error);
    if (error && status.type() != std::filesystem::file_type::not_found)
      {
        std::string reason = error.message();
        if (!reason.empty())
          reason[0] = std::tolower(static_cast<unsigned char>(reason[0]));
        throw InputError(file, entry, "cannot be read: " + reason);
      }
    return status.type();
  }
} // namespace clothsim
