// Running gmsh for one mesh read: the session and its message log, gmsh's errors as
// InputErrors, and generating a missing .msh from the .geo of the same stem.

#include "mesh/gmsh_reader_detail.h"

#include "io/input_error.h"
#include "io/input_file.h"
#include "mesh/child_process.h"

#include <gmsh.h>
#include <unistd.h>

#include <filesystem>
#include <memory>

namespace clothsim::mesh::detail
{
  namespace
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
    // std::exception in later versions) into an InputError with `context` in front.
    template <typename Function>
    void
    call_gmsh(const std::string &msh_file, const std::string &context, Function &&f)
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
          throw InputError(msh_file, "", context + ": " + message);
        }
      catch (const char *message)
        {
          throw InputError(msh_file, "", context + ": " + message);
        }
      catch (const std::exception &error)
        {
          throw InputError(msh_file, "", context + ": " + error.what());
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

      // Throws an InputError with the first error logged since construction, if any.
      void
      throw_first_error(const std::string &msh_file, const std::string &context) const
      {
        const std::string        prefix = "Error: ";
        std::vector<std::string> log;
        gmsh::logger::get(log);
        for (std::size_t i = n_old_lines; i < log.size(); ++i)
          if (log[i].compare(0, prefix.size(), prefix) == 0)
            throw InputError(msh_file, "", context + ": " + log[i].substr(prefix.size()));
      }

    private:
      std::size_t n_old_lines;
    };


    // Writes the .msh for `geo_file` next to it: to a temporary name first, then renamed,
    // so that a concurrent reader (another MPI rank) never sees a half-written file.
    void
    generate_msh(const std::string &msh_file, const std::filesystem::path &geo_file)
    {
      const std::string context = "generating it from " + geo_file.string() + " failed";
      std::filesystem::path partial_file = msh_file;
      partial_file.replace_filename(partial_file.stem().string() + ".partial-" +
                                    std::to_string(::getpid()) + ".msh");
      call_gmsh(msh_file, context, [&]() {
        // Errors reported through the log, not thrown: a .geo syntax error thrown out of
        // gmsh's parser leaves the parser broken for every later .geo in this process.
        {
          const GmshLog log;
          gmsh::option::setNumber("General.AbortOnError", 0);
          gmsh::open(geo_file.string());
          log.throw_first_error(msh_file, context);
          gmsh::model::mesh::generate(2);
          log.throw_first_error(msh_file, context);
          gmsh::option::setNumber("General.AbortOnError", 2);
        }

        // Save all elements, also when no physical group holds the surface.
        gmsh::option::setNumber("Mesh.SaveAll", 1);
        gmsh::option::setNumber("Mesh.Binary", 0);
        gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
        gmsh::write(partial_file.string());
        gmsh::clear();
      });

      std::error_code error;
      std::filesystem::rename(partial_file, msh_file, error);
      if (error)
        {
          std::filesystem::remove(partial_file, error);
          throw InputError(msh_file, "", context + ": cannot write the .msh file");
        }
    }
  } // namespace


  RawMesh
  load_with_gmsh(const std::string &msh_file)
  {
    namespace fs = std::filesystem;

    const fs::file_type msh_type = input_file_type(msh_file);
    const bool          have_msh = msh_type != fs::file_type::not_found;
    const fs::path      geo_file = fs::path(msh_file).replace_extension(".geo");
    if (!have_msh && input_file_type(geo_file.string()) == fs::file_type::not_found)
      throw InputError(msh_file,
                       "",
                       "mesh file not found (nor a .geo to generate it from)");
    if (have_msh && msh_type != fs::file_type::regular)
      throw InputError(msh_file, "", "not a regular file");

    // Everything once in a child process first (mesh/child_process.h): gmsh crashes on
    // some malformed files. The child also generates a missing .msh; a crash after that
    // leaves a .msh that must not stay.
    const auto read = [&](const bool generate) {
      std::unique_ptr<GmshSession> session;
      call_gmsh(msh_file, "gmsh cannot start", [&]() {
        session = std::make_unique<GmshSession>();
      });
      if (generate)
        generate_msh(msh_file, geo_file);
      RawMesh mesh;
      call_gmsh(msh_file, "gmsh cannot read it", [&]() {
        gmsh::open(msh_file);
        mesh = read_model(msh_file);
      });
      return mesh;
    };
    RawMesh raw;
    try
      {
        run_in_child_process(msh_file, "gmsh reading it", [&]() { read(!have_msh); });
        raw = read(false);
      }
    catch (...)
      {
        if (!have_msh)
          remove_generated_msh(msh_file);
        throw;
      }
    raw.generated = !have_msh;
    return raw;
  }


  void
  remove_generated_msh(const std::string &msh_file)
  {
    std::error_code error;
    std::filesystem::remove(msh_file, error);
  }
} // namespace clothsim::mesh::detail
