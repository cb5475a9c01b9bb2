#include "scene/scene.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

#include "io/collective.h"
#include "io/input_error.h"
#include "scene/probes.h"

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


  Scene::Scene()
    : prm(std::make_unique<ParameterHandler>())
    , serial_mesh(std::make_unique<Triangulation<2, 3>>())
  {}


  Scene::~Scene() = default;


  std::unique_ptr<Scene>
  load_scene(const std::string              &parameter_file,
             const std::vector<std::string> &overrides,
             const MPI_Comm                  communicator)
  {
    auto scene       = std::make_unique<Scene>();
    scene->input     = read_parameters(*scene->prm, parameter_file, overrides);
    scene->mesh_file = resolve_mesh_file(scene->input);

    // Rank 0 first: it may have to generate the .msh from its .geo. An error on any
    // rank reaches all of them (io/collective.h).
    const bool is_root = Utilities::MPI::this_mpi_process(communicator) == 0;
    io::run_collectively(communicator, [&]() {
      if (is_root)
        scene->groups = mesh::read_gmsh(scene->mesh_file, *scene->serial_mesh);
    });
    io::run_collectively(communicator, [&]() {
      if (!is_root)
        scene->groups = mesh::read_gmsh(scene->mesh_file, *scene->serial_mesh);
    });

    scene->model                 = std::make_unique<ClothModel>(communicator,
                                                scene->parameters(),
                                                parameter_file,
                                                *scene->serial_mesh,
                                                scene->groups);
    const Parameters &parameters = scene->parameters();
    if (parameters.time.integrator == Integrator::linear_static ||
        parameters.time.integrator == Integrator::arc_length)
      {
        // K0 u = f eliminates the pinned dofs with their values, and the arc-length
        // path is parametrised by the loads' factor alone: zero ones only.
        VectorType pinned;
        scene->model->initialize_owned(pinned);
        scene->model->apply_pinned_displacement(1., pinned);
        if (pinned.linfty_norm() != 0.)
          throw InputError(parameter_file,
                           "Constraints/Pinned displacement",
                           std::string("'Time/Integrator = ") +
                             (parameters.time.integrator == Integrator::arc_length
                                ? "arc length"
                                : "linear static") +
                             "' takes loads only: the pinned displacements and "
                             "prescribed rotations must be zero (here up to " +
                             std::to_string(pinned.linfty_norm()) +
                             " m or rad at the full load); use 'static'");
      }
    const mesh::Discretization &discretization = scene->model->get_discretization();
    scene->probes =
      locate_probes(discretization,
                    parameters.output.probes,
                    parameters.output.probe_tolerance * discretization.longest_edge(),
                    parameter_file);
    return scene;
  }
} // namespace clothsim
