#include "app/study_run.h"

#include <deal.II/base/conditional_ostream.h>

#include "app/scene_runner.h"
#include "scene/scene.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace clothsim
{
  namespace
  {
    // A vertex's reference position rounded to 1e-9 (m): the same point in two meshes
    // (a coarse vertex survives refinement) gets the same key.
    std::array<long long, 3>
    position_key(const std::array<double, 6> &vertex)
    {
      return {{std::llround(vertex[0] * 1e9),
               std::llround(vertex[1] * 1e9),
               std::llround(vertex[2] * 1e9)}};
    }

    // For each of a's vertices that b has too: (index in a, index in b).
    std::vector<std::pair<unsigned int, unsigned int>>
    shared_vertices(const std::vector<std::array<double, 6>> &a,
                    const std::vector<std::array<double, 6>> &b)
    {
      std::map<std::array<long long, 3>, unsigned int> index_of;
      for (unsigned int i = 0; i < b.size(); ++i)
        index_of[position_key(b[i])] = i;
      std::vector<std::pair<unsigned int, unsigned int>> pairs;
      for (unsigned int i = 0; i < a.size(); ++i)
        {
          const auto found = index_of.find(position_key(a[i]));
          if (found != index_of.end())
            pairs.emplace_back(i, found->second);
        }
      if (pairs.empty())
        throw std::runtime_error("the two runs share no vertex");
      return pairs;
    }
  } // namespace


  std::string
  parameter_value(const double value)
  {
    std::ostringstream out;
    out << std::setprecision(17) << value;
    return out.str();
  }


  StudyRun
  run_study_case(const std::string              &file,
                 const std::vector<std::string> &overrides,
                 const std::string              &directory,
                 const MPI_Comm                  communicator)
  {
    std::unique_ptr<Scene> scene      = load_scene(file, overrides, communicator);
    const ClothModel      &model      = *scene->model;
    const Parameters      &parameters = scene->parameters();
    StudyRun               run;
    run.overrides = overrides;
    run.unknowns  = model.n_dofs();
    run.time_step = parameters.time.time_step;
    run.end_time  = is_static(parameters.time.integrator) ? 1. : parameters.time.end_time;
    run.probes    = parameters.output.probes;

    ConditionalOStream quiet(std::cout, false);
    const auto         keep_last = [&run, &model, &scene, communicator](const double,
                                                                const VectorType &u) {
      run.vertices = model.get_discretization().vertex_displacements(u);
      run.probe_displacements = probe_displacements(scene->probes, u, communicator);
    };
    const RunOutcome outcome =
      run_loaded_scene(*scene, file, directory, quiet, keep_last);
    run.completed    = outcome.completed;
    run.failure      = outcome.failure;
    run.wall_seconds = outcome.wall_seconds;
    run.summary      = outcome.summary;
    return run;
  }


  std::vector<std::array<double, 6>>
  restrict_to(const std::vector<std::array<double, 6>> &b,
              const std::vector<std::array<double, 6>> &a)
  {
    std::vector<std::array<double, 6>> restricted;
    for (const auto &[in_a, in_b] : shared_vertices(a, b))
      restricted.push_back(b[in_b]);
    return restricted;
  }


  FieldDifference
  field_difference(const std::vector<std::array<double, 6>> &a,
                   const std::vector<std::array<double, 6>> &b)
  {
    FieldDifference difference;
    double          sum_squares = 0.;
    for (const auto &[in_a, in_b] : shared_vertices(a, b))
      {
        double gap2 = 0.;
        for (unsigned int d = 3; d < 6; ++d)
          gap2 += (a[in_a][d] - b[in_b][d]) * (a[in_a][d] - b[in_b][d]);
        sum_squares += gap2;
        difference.largest = std::max(difference.largest, std::sqrt(gap2));
        ++difference.common;
      }
    difference.rms = std::sqrt(sum_squares / difference.common);
    return difference;
  }
} // namespace clothsim
