#pragma once

// A scene: everything a run models, built from a parameter file and checked, before
// anything is written. Used by the clothsim executable and by tests that run scenes
// in-process.

#include "io/parameters.h"
#include "io/probe_location.h"
#include "mesh/gmsh_reader.h"
#include "scene/cloth_model.h"

#include <memory>
#include <string>
#include <vector>

namespace clothsim
{
  // The parameter handler and the mesh as read are held by pointer: their headers
  // (<deal.II/base/parameter_handler.h>, <deal.II/grid/tria.h>) are for the files that
  // use them, not for every file that includes this one.
  struct Scene
  {
    Scene();
    ~Scene();

    std::unique_ptr<ParameterHandler> prm;
    ParameterInput                    input;
    // The mesh file, resolved against the parameter file's directory.
    std::string                          mesh_file;
    std::unique_ptr<Triangulation<2, 3>> serial_mesh;
    mesh::MeshGroups                     groups;
    std::unique_ptr<ClothModel>          model;
    std::vector<ProbeLocation>           probes;

    const Parameters &
    parameters() const
    {
      return input.parameters;
    }
  };

  // Reads and checks the parameter file (with overrides) and the mesh, builds the model
  // and locates the probes. Collective over `communicator`. Throws InputError on bad
  // input.
  std::unique_ptr<Scene>
  load_scene(const std::string              &parameter_file,
             const std::vector<std::string> &overrides,
             const MPI_Comm                  communicator);
} // namespace clothsim
