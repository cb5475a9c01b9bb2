// Air drag and wind (physics/air_drag.h), checked with numbers:
// 0. The kernel against its closed form: ψ = ρ A (C_n |v_n|³ + C_t |v_t|³)/6 and ψ' at
//    one relative velocity, ψ'' against central differences of ψ'.
// 1. Derivatives of the air term alone (a physics::Model of it on the falling plate's
//    mesh, tests/scenes/falling_plate.prm) and of the scene's assembled model (membrane,
//    gravity, inertia, air): (Φ(u+hd) - Φ(u-hd))/2h against ∇Φ·d (relative error below
//    1e-6) and (∇Φ(u+hd) - ∇Φ(u-hd))/2h against H d (below 1e-5), h = 1e-5, as
//    tests/model_terms.cc. Cases: still air and a wind field that varies in space and
//    time on a crumpled lagged geometry (5 cm displacements on 0.2 m triangles, step
//    velocities about 1 m/s); the flat plate moving along its normal (v_t = 0 on every
//    triangle), with and without a wind along the normal; the flat plate moving in its
//    plane (v_n = 0: skin friction alone). The projected tangent is the exact one (ψ is
//    convex), and d·H d >= 0.
// 2. The plate falling flat in still air with backward Euler (tests/scenes/
//    falling_plate.prm: ρ_A = 0.12 kg/m², ρ_air = 1.2 kg/m³, C_n = 1.2, 1 s): the
//    velocity v = sqrt(2 K / m) from statistics.csv reaches v_t = sqrt(2 ρ_A g /
//    (ρ_air C_n)) = 1.2787 m/s within 1 % (backward Euler's steady state is the exact
//    balance; measured 1.2e-6 at 1 s = 7.7 v_t/g, still approaching it), and follows
//    v(t) = v_t tanh(g t / v_t) with backward Euler's first-order error (its local
//    error is dt²/2 v'', summed over t/dt steps): the largest error over the run and
//    the error at t = v_t/g (interpolated), measured 1.38 % and 1.36 % of v_t at dt =
//    0.01 s and half that at 0.005 s (observed order 0.98; asserted 0.8 to 1.2), stay
//    within 20 % of those figures at dt = 0.01 s. The sheet stays flat (elastic energy
//    below 1e-12 J; measured 1e-28 J).
// 3. Energy in still air, with no Rayleigh damping, so that damping_dissipated is the
//    air's work alone. The swinging membrane (params/benchmarks/swing-membrane.prm, N =
//    21, 1 s) with backward Euler: the total energy never rises by more than 1e-9 of the
//    energy the loads released (max |potential|), the air's work never falls and takes
//    more than half of it. The falling plate with the implicit midpoint rule (no
//    dissipation of its own; exact on its quadratic energies): total + air work stays at
//    its start within 1e-8 of the released energy, and the air work never falls. (The
//    midpoint rule blows up on the swinging membrane, README "Time integration"; the
//    average vector field is refused with air.)

#include "physics/air_drag.h"
#include "csv.h"
#include "term_checks.h"
#include "test_support.h"

#include <cmath>
#include <set>

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  const std::string falling_plate = source_path("tests/scenes/falling_plate.prm");
  // As in the falling plate scene.
  const physics::AirProperties air{1.2, 1.2, 0.02};
  const double                 areal_density = 0.12;
  const double                 g             = 9.81;


  // 0. The kernel at one relative velocity.
  bool
  check_kernel(ConditionalOStream &pcout)
  {
    const double       area = 0.5;
    const Tensor<1, 3> normal({0., 0.6, 0.8});
    const Tensor<1, 3> v_t({1., 0., 0.}); // |v_t| = 1, v_t·n = 0
    const double       v_n = -2.;
    const Tensor<1, 3> v_r = v_t + v_n * normal;
    Tensor<1, 3>       first;
    Tensor<2, 3>       second;
    const double psi = physics::air_dissipation(air, area, normal, v_r, &first, &second);
    const double expected_psi =
      air.density * area * (air.normal_drag * 8. + air.tangential_drag * 1.) / 6.;
    const Tensor<1, 3> expected_first =
      0.5 * air.density * area *
      (air.normal_drag * 2. * v_n * normal + air.tangential_drag * 1. * v_t);
    double second_error = 0., second_norm = second.norm();
    for (unsigned int c = 0; c < 3; ++c)
      {
        Tensor<1, 3> shifted = v_r, plus, minus;
        shifted[c] += 1e-6;
        physics::air_dissipation(air, area, normal, shifted, &plus, nullptr);
        shifted[c] -= 2e-6;
        physics::air_dissipation(air, area, normal, shifted, &minus, nullptr);
        for (unsigned int r = 0; r < 3; ++r)
          second_error =
            std::max(second_error,
                     std::abs((plus[r] - minus[r]) / 2e-6 - second[r][c]) / second_norm);
      }
    pcout << "0. kernel: psi = " << psi << " W (closed form " << expected_psi
          << "), |psi'| = " << first.norm() << " N" << std::endl;
    bool passed = check_relative_equal(
      pcout, "psi against its closed form", psi, expected_psi, 1e-14);
    passed &= check_below(pcout,
                          "psi' against its closed form (relative)",
                          (first - expected_first).norm() / expected_first.norm(),
                          1e-14);
    passed &= check_below(pcout,
                          "psi'' against differences of psi' (relative, max entry)",
                          second_error,
                          1e-8);
    return passed;
  }


  // 1. Derivatives of the air term alone, and of the assembled scene with it.
  struct DerivativeCase
  {
    std::string        description;
    physics::WindField wind;
    bool               flat;     // lagged geometry: the flat reference plate
    Tensor<1, 3>       uniform;  // with `flat`: the same step displacement everywhere, m
    double             time = 0; // s
    double             h    = 1e-5; // difference step, relative to d
  };

  bool
  check_derivatives(ConditionalOStream &pcout, const MPI_Comm communicator)
  {
    auto              scene = load_scene(falling_plate, {}, communicator);
    const ClothModel &model = *scene->model;
    const auto        names = model.term_names();
    pcout << "1. derivatives on the falling plate's mesh ("
          << model.get_discretization().n_triangles() << " triangles); terms "
          << joined(names) << std::endl;
    bool passed =
      check_below(pcout,
                  "scene terms other than exactly membrane, gravity, kinetic, air",
                  std::set<std::string>(names.begin(), names.end()) !=
                      std::set<std::string>{"membrane", "gravity", "kinetic", "air"} ||
                    names.size() != 4,
                  0.5);

    const physics::WindField field = [](const Point<3> &x, const double t) {
      return Tensor<1, 3>({3. + std::sin(2. * x[0]), 1. + x[1] * t, 0.5 * x[2]});
    };
    const physics::WindField vertical = [](const Point<3> &, const double) {
      return Tensor<1, 3>({0., 0., 0.4});
    };
    const std::vector<DerivativeCase> cases = {
      {"still air, crumpled", {}, false, {}},
      {"wind field, crumpled", field, false, {}, 0.3},
      {"flat plate along its normal (v_t = 0)", {}, true, Tensor<1, 3>({0., 0., 0.01})},
      {"flat plate along its normal, wind along it (v_t = 0)",
       vertical,
       true,
       Tensor<1, 3>({0., 0., 0.01})},
      // At v_n = 0 the normal part's second derivative has a kink (C_n |v_n|): the
      // difference quotient of the gradient is first order in h there (measured 5.9e-5
      // at h = 1e-5, 60 times the skin friction's C_t), so a smaller h.
      {"flat plate in its plane (v_n = 0)",
       field,
       true,
       Tensor<1, 3>({0.01, -0.02, 0.}),
       0.,
       1e-7},
    };

    const double dt = 0.01;
    for (const DerivativeCase &given : cases)
      {
        VectorType u, d, previous, previous_ghosted;
        for (VectorType *vector : {&u, &d, &previous})
          model.initialize_owned(*vector);
        model.initialize_ghosted(previous_ghosted);
        fill(model, d, 0.01, 0., 7);
        if (given.flat)
          {
            for (const auto &element : model.get_discretization().elements())
              for (unsigned int i = 0; i < 9; ++i)
                if (model.owned_dofs().is_element(element.dofs[i]))
                  u[element.dofs[i]] = given.uniform[i % 3];
            u.compress(VectorOperation::insert);
          }
        else
          {
            fill(model, previous, 0.05, 0., 5);
            fill(model, u, 0.01, 0., 1);
            u += previous;
          }
        previous_ghosted = previous;

        StepTerms terms;
        terms.damping_weight    = 1. / dt;
        terms.previous          = &previous_ghosted;
        terms.time              = given.time;
        terms.projected_tangent = false;

        physics::Model single(model.get_discretization(), model.get_constraints());
        single.add(std::make_unique<physics::AirDrag>(air, given.wind));
        const double      h               = given.h;
        const Derivatives exact           = derivatives(single, model, terms, u, d, h);
        StepTerms         projected_terms = terms;
        projected_terms.projected_tangent = true;
        const Derivatives projected =
          derivatives(single, model, projected_terms, u, d, h);
        pcout << "  " << given.description << ": Phi = " << exact.value
              << " J, grad Phi.d = " << exact.directional
              << " J, d.H d = " << exact.curvature << " J; gradient error "
              << exact.gradient_error << ", Hessian error " << exact.hessian_error
              << std::endl;
        passed &= check_below(pcout,
                              given.description + ": gradient error (relative)",
                              exact.gradient_error,
                              1e-6);
        passed &= check_below(pcout,
                              given.description + ": Hessian error (relative)",
                              exact.hessian_error,
                              1e-5);
        passed &= check_below(pcout,
                              given.description +
                                ": projected tangent's Hessian error (relative)",
                              projected.hessian_error,
                              1e-5);
        passed &=
          check_at_least(pcout, given.description + ": d.H d (J)", exact.curvature, 0.);
        passed &= check_above(pcout,
                              given.description + ": |grad Phi.d| (J)",
                              std::abs(exact.directional),
                              0.);
      }

    // The scene's assembled model (membrane, gravity, inertia, air) at a crumpled state.
    VectorType u, d, predictor, previous, predictor_ghosted, previous_ghosted;
    for (VectorType *vector : {&u, &d, &predictor, &previous})
      model.initialize_owned(*vector);
    model.initialize_ghosted(predictor_ghosted);
    model.initialize_ghosted(previous_ghosted);
    fill(model, previous, 0.05, 0., 5);
    fill(model, predictor, 0.01, 0., 3);
    fill(model, u, 0.01, 0., 1);
    fill(model, d, 0.01, 0., 7);
    predictor += previous;
    u += previous;
    predictor_ghosted = predictor;
    previous_ghosted  = previous;
    StepTerms terms;
    terms.inertia_weight    = 1. / (dt * dt);
    terms.damping_weight    = 1. / dt;
    terms.predictor         = &predictor_ghosted;
    terms.previous          = &previous_ghosted;
    terms.projected_tangent = false;
    const Derivatives all   = derivatives(model, model, terms, u, d, 1e-5);
    pcout << "  assembled scene: Phi = " << all.value << " J; gradient error "
          << all.gradient_error << ", Hessian error " << all.hessian_error << std::endl;
    passed &= check_below(pcout,
                          "assembled scene: gradient error (relative)",
                          all.gradient_error,
                          1e-6);
    passed &= check_below(pcout,
                          "assembled scene: Hessian error (relative)",
                          all.hessian_error,
                          1e-5);
    return passed;
  }


  // 2. The plate falling flat: the velocity after each step (from its kinetic energy)
  // against v_t tanh(g t / v_t).
  struct FallErrors
  {
    double terminal; // |v(end) - v_t| / v_t
    double largest;  // max over the steps |v - v_exact| / v_t
    double at_scale; // the same at t = v_t / g (linear interpolation)
    double elastic;  // largest elastic energy, J
  };

  FallErrors
  fall(ConditionalOStream &pcout, const MPI_Comm communicator, const double dt)
  {
    const std::string directory =
      scratch_directory("clothsim-air-drag-np" +
                        std::to_string(Utilities::MPI::n_mpi_processes(communicator)));
    const SceneRun run =
      run_scene(falling_plate, {"Time/Time step=" + number(dt)}, directory, communicator);
    MPI_Barrier(communicator);
    const double mass = areal_density * run.model().get_discretization().reference_area();
    const double terminal =
      std::sqrt(2. * areal_density * g / (air.density * air.normal_drag));
    const double t_scale = terminal / g;
    const Csv    csv     = read_csv(directory + "/statistics.csv");
    FallErrors   errors{0., 0., 0., 0.};
    double       previous_t = 0., previous_error = 0.;
    for (unsigned int r = 0; r < csv.rows.size(); ++r)
      {
        const double t     = csv.number(r, "time");
        const double v     = std::sqrt(2. * csv.number(r, "kinetic_energy") / mass);
        const double error = (v - terminal * std::tanh(t / t_scale)) / terminal;
        errors.largest     = std::max(errors.largest, std::abs(error));
        errors.elastic     = std::max(errors.elastic, csv.number(r, "elastic_energy"));
        if (r > 0 && previous_t < t_scale && t >= t_scale)
          errors.at_scale =
            std::abs(previous_error + (error - previous_error) * (t_scale - previous_t) /
                                        (t - previous_t));
        if (r + 1 == csv.rows.size())
          errors.terminal = std::abs(v - terminal) / terminal;
        previous_t     = t;
        previous_error = error;
      }
    pcout << "  dt = " << dt << " s (" << csv.rows.size() - 1
          << " steps): v_t = " << terminal << " m/s, v_t/g = " << t_scale
          << " s; terminal velocity error " << errors.terminal
          << ", largest error against the tanh curve " << errors.largest
          << " v_t, at t = v_t/g " << errors.at_scale << " v_t, largest elastic energy "
          << errors.elastic << " J" << std::endl;
    return errors;
  }

  bool
  check_falling_plate(ConditionalOStream &pcout, const MPI_Comm communicator)
  {
    pcout << "2. the plate falling flat in still air, backward Euler" << std::endl;
    const FallErrors coarse = fall(pcout, communicator, 0.01);
    const FallErrors fine   = fall(pcout, communicator, 0.005);
    bool             passed = true;
    const std::vector<std::pair<std::string, FallErrors>> runs = {{"dt = 0.01 s", coarse},
                                                                  {"dt = 0.005 s", fine}};
    for (const auto &[name, errors] : runs)
      {
        passed &= check_below(pcout,
                              std::string(name) + ": |v(1 s) - v_t| / v_t",
                              errors.terminal,
                              0.01);
        passed &= check_below(pcout,
                              std::string(name) + ": largest elastic energy (J)",
                              errors.elastic,
                              1e-12);
      }
    // Measured at dt = 0.01 s: 0.01377 largest, 0.01364 at t = v_t/g (bounds +20 %).
    passed &= check_below(pcout,
                          "dt = 0.01 s: largest |v - v_t tanh(g t/v_t)| / v_t",
                          coarse.largest,
                          0.0166);
    passed &=
      check_below(pcout, "dt = 0.01 s: the same at t = v_t/g", coarse.at_scale, 0.0164);
    const double order = observed_order(coarse.largest, fine.largest);
    passed &= check_above(pcout, "observed order of the largest error", order, 0.8);
    passed &= check_below(pcout, "observed order of the largest error", order, 1.2);
    const double order_at_scale = observed_order(coarse.at_scale, fine.at_scale);
    passed &=
      check_above(pcout, "observed order of the error at t = v_t/g", order_at_scale, 0.8);
    passed &=
      check_below(pcout, "observed order of the error at t = v_t/g", order_at_scale, 1.2);
    return passed;
  }


  // 3. Energy in still air, from statistics.csv (damping_dissipated is the air's work:
  // no Rayleigh damping).
  struct EnergyHistory
  {
    double       scale;             // max |potential_energy|, J
    double       largest_rise;      // max increase of total_energy in a step, J
    double       smallest_work;     // min increase of damping_dissipated in a step, J
    double       drift;             // max |total + dissipated - initial|, J
    double       drift_without_air; // max |total - initial|, J
    double       work;              // damping_dissipated at the end, J
    unsigned int steps;
  };

  EnergyHistory
  energy_history(const MPI_Comm                  communicator,
                 const std::string              &file,
                 const std::vector<std::string> &overrides)
  {
    const std::string directory =
      scratch_directory("clothsim-air-drag-energy-np" +
                        std::to_string(Utilities::MPI::n_mpi_processes(communicator)));
    run_scene(file, overrides, directory, communicator);
    MPI_Barrier(communicator);
    const Csv     csv = read_csv(directory + "/statistics.csv");
    EnergyHistory history{0., -1e300, 1e300, 0., 0., 0., 0};
    const double  initial = csv.number(0, "total_energy");
    for (unsigned int r = 0; r < csv.rows.size(); ++r)
      {
        const double total = csv.number(r, "total_energy");
        const double work  = csv.number(r, "damping_dissipated");
        history.scale =
          std::max(history.scale, std::abs(csv.number(r, "potential_energy")));
        history.drift = std::max(history.drift, std::abs(total + work - initial));
        history.drift_without_air =
          std::max(history.drift_without_air, std::abs(total - initial));
        if (r > 0)
          {
            history.largest_rise =
              std::max(history.largest_rise, total - csv.number(r - 1, "total_energy"));
            history.smallest_work =
              std::min(history.smallest_work,
                       work - csv.number(r - 1, "damping_dissipated"));
          }
        history.work = work;
      }
    history.steps = csv.rows.size() - 1;
    return history;
  }

  bool
  check_energy(ConditionalOStream &pcout, const MPI_Comm communicator)
  {
    bool passed = true;
    {
      const EnergyHistory be =
        energy_history(communicator,
                       source_path("params/benchmarks/swing-membrane.prm"),
                       {"Mesh/Mesh file=../../meshes/swing-21.msh",
                        "Time/Integrator=backward euler",
                        "Time/End time=1",
                        "Air/Density=1.2"});
      pcout << "3a. swinging membrane in still air, backward Euler (" << be.steps
            << " steps): released max|potential| = " << be.scale << " J, air work "
            << be.work << " J, largest change of the total energy in a step "
            << be.largest_rise << " J, smallest air work in a step " << be.smallest_work
            << " J" << std::endl;
      passed &= check_below(pcout,
                            "backward Euler: largest rise of total_energy in a step / "
                            "max|potential|",
                            be.largest_rise / be.scale,
                            1e-9);
      passed &= check_at_least(pcout,
                               "backward Euler: smallest air work in a step (J)",
                               be.smallest_work,
                               0.);
      passed &= check_above(pcout,
                            "backward Euler: air work at the end / max|potential|",
                            be.work / be.scale,
                            0.5);
    }
    {
      // The implicit midpoint rule adds no dissipation of its own, and the falling
      // plate's energies (gravity, kinetic; no strain) are quadratic, which it keeps
      // exactly: total + air work is conserved up to Newton's tolerance.
      const EnergyHistory midpoint =
        energy_history(communicator,
                       falling_plate,
                       {"Time/Integrator=implicit midpoint"});
      pcout << "3b. the falling plate, implicit midpoint (" << midpoint.steps
            << " steps): released max|potential| = " << midpoint.scale << " J, air work "
            << midpoint.work
            << " J, largest |total + air work - initial| = " << midpoint.drift
            << " J, without the air work " << midpoint.drift_without_air << " J"
            << std::endl;
      passed &= check_below(pcout,
                            "midpoint: max |total + air work - initial| / max|potential|",
                            midpoint.drift / midpoint.scale,
                            1e-8);
      passed &= check_above(pcout,
                            "midpoint: the same without the air work (must fail)",
                            midpoint.drift_without_air / midpoint.scale,
                            0.5);
      passed &= check_at_least(pcout,
                               "midpoint: smallest air work in a step (J)",
                               midpoint.smallest_work,
                               0.);
      passed &= check_below(pcout,
                            "midpoint: largest rise of total_energy in a step / "
                            "max|potential|",
                            midpoint.largest_rise / midpoint.scale,
                            1e-9);
    }
    return passed;
  }
} // namespace


int
main(int argc, char **argv)
{
  test::Environment   env(argc, argv);
  ConditionalOStream &pcout        = env.pcout;
  const MPI_Comm      communicator = env.communicator;
  bool                passed       = check_kernel(pcout);
  passed &= check_derivatives(pcout, communicator);
  passed &= check_falling_plate(pcout, communicator);
  passed &= check_energy(pcout, communicator);
  return test::finish(pcout, passed);
}
