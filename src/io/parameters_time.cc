// Section "Time": the integrator, time or load steps, step adaptivity, initial state.

#include "io/parameters.h"

#include <deal.II/base/parameter_handler.h>

namespace clothsim
{
  void
  TimeParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    prm.declare_entry(
      "Integrator",
      "backward euler",
      Patterns::Selection(
        "backward euler|bdf2|implicit midpoint|average vector field|static|linear static|"
        "arc length|symplectic euler|velocity verlet"),
      "'backward euler': implicit dynamics, each step the minimiser of the "
      "incremental potential (first order, damps high frequencies). 'bdf2': "
      "second-order backward differentiation with variable steps (the first "
      "step backward Euler), the same minimisation with other weights. 'implicit "
      "midpoint': second order and symplectic (no numerical damping; energy "
      "oscillates but does not drift): a backward-Euler minimisation over half "
      "the step to the midpoint, then extrapolation. 'average vector field': "
      "the midpoint rule with the force averaged along the step's path instead "
      "of taken at the midpoint (Quispel & McLaren 2008), so that the elastic "
      "and load terms neither gain nor lose energy (exactly for the membrane "
      "and the loads, to fourth order in the step for bending and springs); "
      "two force and tangent evaluations per Newton iteration. 'static': "
      "equilibrium under loads ramped in 'Load steps' equal increments (time = load "
      "factor 0..1). 'linear static': small-displacement analysis, one linear solve "
      "K0 u = f about the reference state (K0 the tangent there, f the loads at full "
      "value): the answer scales with the loads. It takes one load step of size 1 ('Load "
      "steps' and the 'Nonlinear solver' section are not used) and needs the pinned "
      "displacements to be zero. 'arc length': the static equilibrium path by "
      "arc-length continuation (Riks' normal-plane method, Crisfield 1991), which "
      "follows limit points (snap-through) and snap-backs where load control stops: "
      "each step advances a distance along the path in (displacement, load factor) "
      "space, the first by 1/'Load steps' in the load factor; 'Adaptive load steps' "
      "lets it grow or shrink by the corrector's iterations; the run ends where the "
      "path reaches load factor 1 (solved there exactly), and the load factor is the "
      "time column of the output files (solution.pvd numbers the frames by step, "
      "since the load factor can fall). Loads only (zero pinned displacements), no "
      "contact; the corrector is full Newton with the exact tangent (the 'Nonlinear "
      "solver' tolerances and 'Maximum iterations' apply, its method, line search and "
      "tangent do not), and past a limit point the tangent is indefinite: 'Linear "
      "solver/Method' must be 'direct' or 'gmres'. With MUMPS the log reports the "
      "tangent's negative eigenvalues (unstable modes) where their number changes. "
      "'symplectic "
      "euler' (v first, then x; first order) and 'velocity verlet' (second "
      "order): explicit, one force evaluation per step, stable only below the "
      "critical step 2/omega_max, which the run estimates and prints (a warning "
      "if 'Time step' exceeds it); they need a lumped mass on every unknown "
      "(Model = mass-spring, or fem without bending).");
    prm.declare_entry("End time", "2", Patterns::Double(0., 1e9), "Simulated time in s.");
    prm.declare_entry("Time step",
                      "0.0166666666666667",
                      Patterns::Double(1e-12, 1e6),
                      "Time step dt in s (backward euler).");
    prm.declare_entry(
      "Maximum step halvings",
      "8",
      Patterns::Integer(0, 30),
      "A step whose Newton solve fails is retried with half the step, at most "
      "this many times in a row; then the run stops with an error.");
    prm.declare_entry(
      "Minimum time step fraction",
      "1e-6",
      Patterns::Double(1e-15, 1.),
      "Progress guard: the run stops with an error (exit code 2) when the step it "
      "would take next (after halvings, or as the error control of 'Adaptive time "
      "steps' proposes it) is below this fraction of 'Time step' (static mode: of "
      "the first load increment 1/'Load steps'). Such a run could not reach "
      "'End time' in reasonable time, e.g. an unreachable 'Accuracy target'.");
    prm.declare_entry("Load steps",
                      "10",
                      Patterns::Integer(1, 100000),
                      "Number of equal load increments in static mode (the first "
                      "increment's size 1/N when 'Adaptive load steps' is on).");
    prm.declare_entry(
      "Adaptive time steps",
      "false",
      Patterns::Bool(),
      "Implicit dynamics: choose each step from a local error estimate (the "
      "difference to an explicit predictor of the method's order, scaled by the "
      "methods' error constants; see time/time_stepper.h). A step whose estimate "
      "exceeds 'Error tolerance' + 'Relative error tolerance' x max|u| is "
      "rejected and retried smaller (counted in statistics.csv); accepted steps "
      "grow by at most 2x. 'Time step' is the first step. Newton then also "
      "stops once a full step moves no coordinate by more than a tenth of 'Error "
      "tolerance' (solving further is below the truncation error).");
    prm.declare_entry("Error tolerance",
                      "1e-4",
                      Patterns::Double(0., 1e3),
                      "Absolute local error tolerance per step in m (adaptive steps).");
    prm.declare_entry("Relative error tolerance",
                      "0",
                      Patterns::Double(0., 1.),
                      "Local error tolerance relative to the largest displacement "
                      "(adaptive steps).");
    prm.declare_entry("Maximum time step",
                      "0.1",
                      Patterns::Double(1e-12, 1e6),
                      "Largest step in s that adaptive stepping may take.");
    prm.declare_entry(
      "Accuracy target",
      "0",
      Patterns::Double(0., 1e3),
      "0: off. Otherwise the error in m the run may accumulate by the end: it "
      "turns on 'Adaptive time steps' with the tolerance of each step set to "
      "target x dt / 'End time' (error per unit step), so that the accepted "
      "local error estimates add up to at most the target; 'Error tolerance' and "
      "'Relative error tolerance' are then not used, and Newton stops at a tenth "
      "of each step's tolerance. The run reports that sum, its estimated error, "
      "at the end. Implicit dynamic integrators with a converging Newton method.");
    prm.declare_entry("Initial displacement",
                      "0; 0; 0",
                      Patterns::List(Patterns::Anything(), 3, 3, ";"),
                      "Displacement at t = 0 in m: three expressions 'ux; uy; uz' in the "
                      "reference coordinates x, y, z (m), e.g. a mode shape "
                      "'0; 0; 0.01*sin(pi*x)*sin(pi*y)'. Pinned vertices follow 'Pinned "
                      "displacement' instead. Dynamic integrators only.");
    prm.declare_entry("Initial velocity",
                      "0; 0; 0",
                      Patterns::List(Patterns::Anything(), 3, 3, ";"),
                      "Velocity at t = 0 in m/s: 'vx; vy; vz' in x, y, z (m). Dynamic "
                      "integrators only.");
    prm.declare_entry("Maximum arc-length steps",
                      "1000",
                      Patterns::Integer(1, 1000000),
                      "'arc length': a path that has not reached load factor 1 after "
                      "this many steps stops the run with an error (exit code 2), its "
                      "output kept.");
    prm.declare_entry(
      "Adaptive load steps",
      "false",
      Patterns::Bool(),
      "Static mode: after an increment that Newton solves in at most 6 iterations "
      "the next one is 1.5 times larger (never more than 1/'Load steps' times 4); "
      "a failed increment is halved as always.");
    prm.leave_subsection();
  }

  void
  TimeParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    const std::string name   = prm.get("Integrator");
    integrator               = name == "static"          ? Integrator::static_load_steps
                               : name == "linear static" ? Integrator::linear_static
                               : name == "arc length"    ? Integrator::arc_length
                               : name == "bdf2"          ? Integrator::bdf2
                               : name == "implicit midpoint" ? Integrator::implicit_midpoint
                               : name == "average vector field" ? Integrator::average_vector_field
                               : name == "symplectic euler" ? Integrator::symplectic_euler
                               : name == "velocity verlet"  ? Integrator::velocity_verlet
                                                            : Integrator::backward_euler;
    end_time                 = prm.get_double("End time");
    time_step                = prm.get_double("Time step");
    max_step_halvings        = prm.get_integer("Maximum step halvings");
    minimum_step_fraction    = prm.get_double("Minimum time step fraction");
    load_steps               = prm.get_integer("Load steps");
    adaptive_load_steps      = prm.get_bool("Adaptive load steps");
    maximum_arc_length_steps = prm.get_integer("Maximum arc-length steps");
    adaptive_time_steps      = prm.get_bool("Adaptive time steps");
    error_tolerance          = prm.get_double("Error tolerance");
    relative_error_tolerance = prm.get_double("Relative error tolerance");
    maximum_time_step        = prm.get_double("Maximum time step");
    accuracy_target          = prm.get_double("Accuracy target");
    if (accuracy_target > 0.)
      adaptive_time_steps = true;
    initial_displacement = prm.get("Initial displacement");
    initial_velocity     = prm.get("Initial velocity");
    prm.leave_subsection();
  }
} // namespace clothsim
