#include "scene/scene.h"

#include <deal.II/base/mpi.h>

#include "io/collective.h"
#include "io/input_error.h"

#include <filesystem>
#include <sstream>

namespace clothsim
{
  namespace
  {
    // Mesh path as written in the parameter file, relative to that file's directory.
    std::string
    resolve_mesh_file(const ParameterInput &input)
    {
      const std::filesystem::path mesh = input.parameters.scene.mesh_file;
      if (mesh.is_absolute() || input.directory.empty())
        return mesh.lexically_normal().string();
      return (std::filesystem::path(input.directory) / mesh).lexically_normal().string();
    }
  } // namespace


  std::unique_ptr<Scene>
  load_scene(const std::string              &parameter_file,
             const std::vector<std::string> &overrides,
             const MPI_Comm                  communicator)
  {
    auto scene       = std::make_unique<Scene>();
    scene->input     = read_parameters(scene->prm, parameter_file, overrides);
    scene->mesh_file = resolve_mesh_file(scene->input);

    // Rank 0 first: it may have to generate the .msh from its .geo. An error on any
    // rank reaches all of them (io/collective.h).
    const bool is_root = Utilities::MPI::this_mpi_process(communicator) == 0;
    io::run_collectively(communicator, [&]() {
      if (is_root)
        scene->groups = mesh::read_gmsh(scene->mesh_file, scene->serial_mesh);
    });
    io::run_collectively(communicator, [&]() {
      if (!is_root)
        scene->groups = mesh::read_gmsh(scene->mesh_file, scene->serial_mesh);
    });

    scene->model = std::make_unique<ClothModel>(communicator,
                                                scene->parameters(),
                                                parameter_file,
                                                scene->serial_mesh,
                                                scene->groups);
    std::vector<std::pair<std::string, Point<3>>> points;
    for (const Probe &probe : scene->parameters().output.probes)
      points.emplace_back(probe.name, probe.reference_point);
    const mesh::Discretization &discretization = scene->model->get_discretization();
    scene->probes                              = discretization.locate_probes(points);
    // Every point of a triangle lies within its longest edge of each of its vertices: a
    // probe farther from the nearest vertex is not on the surface.
    const double tolerance = discretization.longest_edge();
    for (const ProbeLocation &probe : scene->probes)
      if (!(probe.distance <= tolerance))
        {
          std::ostringstream message;
          message << "probe '" << probe.name << "' is " << probe.distance
                  << " m from the nearest mesh vertex (" << probe.reference_point[0]
                  << ", " << probe.reference_point[1] << ", " << probe.reference_point[2]
                  << "), farther than the mesh's longest edge (" << tolerance
                  << " m): it must lie on the cloth's surface";
          throw InputError(parameter_file, "Output/Probes", message.str());
        }
    return scene;
  }
} // namespace clothsim
