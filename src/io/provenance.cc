#include "io/provenance.h"

#include <deal.II/base/config.h>

#include <Trilinos_version.h>
#include <clothsim_revision.h> // generated at build time (scripts/revision.cmake)
#include <dmumps_c.h>
#include <gmsh.h>

#include <ctime>

namespace clothsim::io
{
  namespace
  {
    std::string invocation = "(not recorded)";
    std::string start_date = "(not recorded)";
    std::string blas       = "BLAS (not recorded)";

    // An argument as a shell would need it: quoted when it holds anything but plain
    // characters.
    std::string
    quoted(const std::string &argument)
    {
      if (!argument.empty() && argument.find_first_not_of(
                                 "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                 "0123456789_-+=./:,@%") == std::string::npos)
        return argument;
      std::string text = "'";
      for (const char c : argument)
        text += c == '\'' ? std::string("'\\''") : std::string(1, c);
      return text + "'";
    }
  } // namespace


  void
  record_invocation(const int argc, const char *const *argv)
  {
    invocation.clear();
    for (int i = 0; i < argc; ++i)
      invocation += (i == 0 ? "" : " ") + quoted(argv[i]);
    const std::time_t now = std::time(nullptr);
    char              text[32];
    std::tm           utc{};
    gmtime_r(&now, &utc);
    std::strftime(text, sizeof(text), "%Y-%m-%d %H:%M:%S UTC", &utc);
    start_date = text;
  }


  void
  record_blas(const std::string &description)
  {
    blas = description;
  }


  std::string
  version_line()
  {
    return std::string("clothsim ") + CLOTHSIM_VERSION + " (git " +
           CLOTHSIM_GIT_REVISION + ")";
  }


  std::string
  libraries_line()
  {
    char mpi_library[MPI_MAX_LIBRARY_VERSION_STRING];
    int  length = 0;
    MPI_Get_library_version(mpi_library, &length);
    std::string mpi(mpi_library, length);
    // Open MPI's string goes on with its build details after the first comma.
    mpi = mpi.substr(0, mpi.find_first_of(",\n"));
    return std::string("deal.II ") + DEAL_II_PACKAGE_VERSION + ", Trilinos " +
           TRILINOS_VERSION_STRING + ", MUMPS " + MUMPS_VERSION + ", gmsh " +
           GMSH_API_VERSION + ", " + mpi + ", " + blas;
  }


  std::vector<std::string>
  provenance_lines(const MPI_Comm communicator)
  {
    int ranks = 1;
    MPI_Comm_size(communicator, &ranks);
    return {version_line(),
            libraries_line(),
            "run started " + start_date + " on " + std::to_string(ranks) + " MPI rank" +
              (ranks == 1 ? "" : "s"),
            "command: " + invocation};
  }
} // namespace clothsim::io
