// Running gmsh for one mesh read (session, log and errors: mesh/gmsh_session.h), and
// generating a missing .msh from the .geo of the same stem.

#include "mesh/gmsh_reader_detail.h"

#include "io/input_error.h"
#include "io/input_file.h"
#include "mesh/child_process.h"
#include "mesh/gmsh_session.h"

#include <gmsh.h>
#include <unistd.h>

#include <filesystem>
#include <memory>

namespace clothsim::mesh::detail
{
  namespace
  {
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
