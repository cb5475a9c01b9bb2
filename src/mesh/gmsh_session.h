#pragma once

// Running gmsh in-process: a session, gmsh's exceptions as InputErrors, and its message
// log (for errors gmsh reports instead of throwing). Used by mesh/gmsh_session.cc and
// mesh/surface_mesh.cc. Not part of the interface.

#include "io/input_error.h"

#include <gmsh.h>

#include <cstddef>
#include <exception>
#include <string>
#include <vector>

namespace clothsim::mesh::detail
{
  // gmsh::initialize() on construction, gmsh::finalize() on destruction (also
  // unwinding).
  class GmshSession
  {
  public:
    GmshSession()
    {
      gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
      try
        {
          gmsh::option::setNumber("General.Terminal", 0);
        }
      catch (...)
        {
          gmsh::finalize();
          throw;
        }
    }

    ~GmshSession()
    {
      try
        {
          gmsh::finalize();
        }
      catch (...)
        {}
    }

    GmshSession(const GmshSession &) = delete;
    GmshSession &
    operator=(const GmshSession &) = delete;
  };


  // Runs `f` (calls into gmsh) and turns what gmsh throws (std::string in gmsh 4.8,
  // std::exception in later versions) into an InputError on `file` with `context` in
  // front.
  template <typename Function>
  void
  call_gmsh(const std::string &file, const std::string &context, Function &&f)
  {
    try
      {
        f();
      }
    catch (const InputError &)
      {
        throw;
      }
    catch (const std::string &message)
      {
        throw InputError(file, "", context + ": " + message);
      }
    catch (const char *message)
      {
        throw InputError(file, "", context + ": " + message);
      }
    catch (const std::exception &error)
      {
        throw InputError(file, "", context + ": " + error.what());
      }
  }


  // gmsh's message log while it lives (the logger is stopped also when unwinding: a
  // logger left running would carry its messages over to later gmsh sessions).
  class GmshLog
  {
  public:
    GmshLog()
    {
      gmsh::logger::start();
      std::vector<std::string> log;
      gmsh::logger::get(log);
      n_old_lines = log.size();
    }

    ~GmshLog()
    {
      try
        {
          gmsh::logger::stop();
        }
      catch (...)
        {}
    }

    GmshLog(const GmshLog &) = delete;
    GmshLog &
    operator=(const GmshLog &) = delete;

    // Throws an InputError on `file` with the first error logged since construction, if
    // any.
    void
    throw_first_error(const std::string &file, const std::string &context) const
    {
      const std::string        prefix = "Error: ";
      std::vector<std::string> log;
      gmsh::logger::get(log);
      for (std::size_t i = n_old_lines; i < log.size(); ++i)
        if (log[i].compare(0, prefix.size(), prefix) == 0)
          throw InputError(file, "", context + ": " + log[i].substr(prefix.size()));
    }

  private:
    std::size_t n_old_lines;
  };
} // namespace clothsim::mesh::detail
