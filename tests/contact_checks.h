#pragma once

// What the contact tests share: the step potential of a contact model against
// differences (tests/contact_derivatives.cc, tests/mesh_contact.cc) and reading a contact
// run's output (tests/contact_scenes.cc, tests/mesh_contact_scenes.cc).

#include "extreme_runs.h"
#include "physics/contact_term.h"
#include "physics/friction_term.h"
#include "physics/model.h"
#include "scene/scene.h"
#include "term_checks.h"

namespace clothsim::test
{
  // The barrier and friction of `obstacles` (with the thickness and stiffness of
  // params/contact/sheet-on-sphere.prm) on the sheet of `mesh` flat in z = 0: after
  // begin_step (friction lagged at rest), at least `contacts` contacts on all ranks, and
  // the step potential's gradient and exact Hessian against central differences (relative
  // 1e-5) at displacements within 1 mm of the start, with slips below and above the
  // static range; the projected tangent positive along the difference's direction.
  inline bool
  check_contact_terms(ConditionalOStream                   &pcout,
                      const std::string                    &mesh,
                      const std::vector<physics::Obstacle> &obstacles,
                      const unsigned int                    contacts)
  {
    const double dt    = 1. / 60.;
    const auto   scene = load_scene(source_path("params/contact/sheet-on-sphere.prm"),
                                  {"Mesh/Mesh file=" + mesh},
                                  MPI_COMM_WORLD);
    const ClothModel &model     = *scene->model;
    const auto       &mesh_data = model.get_discretization();
    VectorType        masses;
    model.lumped_masses(masses);
    const ContactParameters &given   = scene->parameters().contact;
    auto                     contact = std::make_unique<physics::ObstacleContact>(
      obstacles,
      physics::ContactSettings{given.thickness,
                               given.barrier_acceleration,
                               given.slip_velocity},
      mesh_data,
      masses);
    physics::ObstacleContact &barrier = *contact;
    physics::Model            terms(mesh_data, model.get_constraints());
    terms.add(std::move(contact));
    terms.add(std::make_unique<physics::ContactFriction>(barrier));

    VectorType u_n, u_new, u, d;
    for (VectorType *vector : {&u_n, &u_new, &u, &d})
      model.initialize_owned(*vector);
    barrier.begin_step(0., dt, u_n, u_new, model.get_constraints());
    const unsigned int lagged =
      Utilities::MPI::sum(static_cast<unsigned int>(barrier.lagged_contacts().size()),
                          MPI_COMM_WORLD);
    bool      passed = check_at_least(pcout, "contacts with friction", lagged, contacts);
    StepTerms step;
    step.time = dt;
    for (const bool projected : {false, true})
      for (const double slip : {2e-6, 2e-3})
        {
          fill(model, u, slip, 0., 3);
          fill(model, d, 1., 0., 5);
          step.projected_tangent = projected;
          const Derivatives D    = derivatives(terms, model, step, u, d, 1e-3 * slip);
          const std::string what = std::string(projected ? "projected" : "exact") +
                                   ", slips of " + std::to_string(slip) + " m: ";
          passed &= check_below(pcout,
                                what + "gradient against differences",
                                D.gradient_error,
                                1e-5);
          if (!projected)
            passed &= check_below(pcout,
                                  what + "Hessian against differences",
                                  D.hessian_error,
                                  1e-5);
          else
            passed &= check_above(pcout,
                                  what + "d·H d of the projected tangent",
                                  D.curvature,
                                  0.);
        }
    return passed;
  }

  // The centre probe's displacement at the output time closest to t.
  inline Tensor<1, 3>
  centre_at(const std::filesystem::path &directory, const double t)
  {
    const Csv    probes = read_csv((directory / "probes.csv").string());
    double       best   = std::numeric_limits<double>::infinity();
    Tensor<1, 3> u;
    for (unsigned int r = 0; r < probes.rows.size(); ++r)
      if (probes.rows[r][probes.column("probe")] == "center" &&
          std::abs(probes.number(r, "time") - t) < best)
        {
          best = std::abs(probes.number(r, "time") - t);
          u    = Tensor<1, 3>(
            {probes.number(r, "ux"), probes.number(r, "uy"), probes.number(r, "uz")});
        }
    return u;
  }

  // The centre's acceleration from the second difference of its x at 0.2, 0.4, 0.6 s.
  inline double
  acceleration(const std::filesystem::path &directory)
  {
    const double h = 0.2;
    return (centre_at(directory, 0.6)[0] - 2. * centre_at(directory, 0.4)[0] +
            centre_at(directory, 0.2)[0]) /
           (h * h);
  }

  // A sheet on a ball turning at ω about x follows the ball's top, which moves along
  // -ω y: the centre's displacement that way at 1 s is above 5 cm.
  inline bool
  check_follows_top(ConditionalOStream          &pcout,
                    const std::string           &name,
                    const std::filesystem::path &directory,
                    const double                 omega)
  {
    const double along = -centre_at(directory, 1.)[1] * (omega > 0. ? 1. : -1.);
    return check_above(pcout,
                       name +
                         ": the centre's displacement along the top's motion at 1 s, m",
                       along,
                       0.05);
  }

  // A support taken away (tests/contact_scenes, tests/mesh_contact_scenes): the sheet at
  // rest on obstacle 1 ('ball', 4 mm below it), gravity tilted by θ = 10° and μ = 0.3,
  // which hold it (backward Euler, steps of 1/60 s); the obstacle is removed at 0.31 s
  // as it drops 100 m within that step (a removed obstacle carries no vertex along, nor
  // keeps its friction). The settings beyond the obstacle's shape:
  inline const double removed_support_tilt = numbers::PI / 18.;

  inline std::vector<std::string>
  removed_support_settings()
  {
    const double g = 9.81, theta = removed_support_tilt;
    return {"Obstacle 1/Friction=0.3",
            "Loads/Gravity=" + number(g * std::sin(theta)) + ", 0, " +
              number(-g * std::cos(theta)),
            "Time/Integrator=backward euler",
            "Time/End time=0.6",
            "Obstacle 1/Translation=0; 0; -100*(t>0.31)",
            "Obstacle 1/Removed at=0.31"};
  }

  // Such a run (in `directory`): from 0.3 s the sheet falls freely, its centre by
  // g τ (τ + dt) / 2 after a time τ (backward Euler from rest under a constant g:
  // u_n = g dt² n (n + 1) / 2), within 0.5 % of that (the creep of the resting sheet);
  // and no row after 0.3 s has a force or contact of the obstacle.
  inline bool
  check_free_fall(ConditionalOStream          &pcout,
                  const std::string           &name,
                  const std::filesystem::path &directory)
  {
    const double       g = 9.81, theta = removed_support_tilt;
    const double       start = 0.3, end = 0.6, dt = 1. / 60.;
    const Tensor<1, 3> gravity({g * std::sin(theta), 0., -g * std::cos(theta)});
    const double       tau      = end - start;
    const Tensor<1, 3> expected = 0.5 * tau * (tau + dt) * gravity;
    const Tensor<1, 3> fallen   = centre_at(directory, end) - centre_at(directory, start);
    bool               passed   = check_below(pcout,
                              name + ": |centre's fall - g τ (τ + dt) / 2| / its length",
                              (fallen - expected).norm() / expected.norm(),
                              5e-3);
    const Csv          statistics = read_csv((directory / "statistics.csv").string());
    double             largest    = 0.;
    unsigned int       rows       = 0;
    for (unsigned int r = 0; r < statistics.rows.size(); ++r)
      if (statistics.number(r, "time") > start + 0.5 * dt)
        {
          ++rows;
          largest = std::max({largest,
                              std::abs(statistics.number(r, "ball_force_x")),
                              std::abs(statistics.number(r, "ball_force_y")),
                              std::abs(statistics.number(r, "ball_force_z")),
                              statistics.number(r, "ball_contacts")});
        }
    passed &= check_above(pcout, name + ": rows after the removal", rows, 0.5);
    passed &= check_at_most(pcout,
                            name + ": largest force (N) or contacts after the removal",
                            largest,
                            0.);
    return passed;
  }

  // Every row of the run's statistics.csv has the cloth apart from every obstacle: its
  // vertices and contact pairs, and (`whole_surface`, with edge contact) every point of
  // its triangles.
  inline bool
  check_outside(ConditionalOStream          &pcout,
                const std::string           &name,
                const std::filesystem::path &directory,
                const bool                   whole_surface = true)
  {
    const Csv statistics = read_csv((directory / "statistics.csv").string());
    double    closest = std::numeric_limits<double>::infinity(), surface = closest;
    for (unsigned int r = 0; r < statistics.rows.size(); ++r)
      {
        closest = std::min(closest, statistics.number(r, "contact_min_distance"));
        surface = std::min(surface, statistics.number(r, "contact_surface_distance"));
      }
    bool passed =
      check_above(pcout, name + ": smallest cloth-obstacle distance, m", closest, 0.);
    if (whole_surface)
      passed &= check_above(pcout,
                            name + ": smallest distance of the cloth's triangles, m",
                            surface,
                            0.);
    return passed;
  }
} // namespace clothsim::test
