// When Newton stops (solvers/newton_solver.h, solvers/energy_line_search.h):
// 1. A line search that finds no decrease fails the solve at once. A problem whose
//    residual is not the gradient of its objective (F = -∇Φ, so the Newton direction
//    climbs Φ although F·d < 0) must fail after one iteration with the line search's
//    message; before, NOX went on from a step of 2^-30 until the iteration cap (measured
//    on a folding step of the swinging sheet: 175 iterations that changed nothing).
//    1b. So does a stall: Φ with a jump just ahead of the iterate along Newton's exact
//    direction, so that each search keeps a shorter step (2⁻¹⁴, 2⁻¹⁵, ...) and ‖F‖
//    stays: the solve fails naming the stall after at most 4 iterations (before: it
//    went on until no step of 2⁻³⁰ decreased Φ), and naming the last update's largest
//    entry (NonlinearProblem::describe_update: Newton's update -u is largest at u_9).
//    1c. An exception thrown by the problem (a defect, which under MPI may come from one
//    rank only) leaves the solve as it is, and is not taken for a failed solve to retry:
//    retried on one rank, it left a two-rank run waiting for 33 minutes.
// 2. 'Truncation error fraction' (stop at a fraction of the step's estimated local
//    error): on the swinging sheet (params/benchmarks/swing.prm, N = 21, first 0.5 s,
//    where it starts to fold) with a fraction of 0.1 against the scene's fixed tolerance
//    (1e-6 m):
//    - fewer Newton iterations: at most 75 % (measured: 100 against 172, 58 %);
//    - a change of the motion well below the time discretisation's: the largest probe
//      difference at the end at most a quarter of the difference between the run and
//      the same run at dt/2 (measured: 1.08 cm against 6.7 cm, 16 %).
// 3. 'Truncation error norm = kinetic' (the swing scene's) against 'largest', both at the
//    scene's fraction 0.03: at most 95 % of the Newton iterations (measured: 100 against
//    111), and the probes within a quarter of the dt/2 difference of the tight run
//    (measured: 1.7e-5 m).

#include <deal.II/base/parameter_handler.h>

#include "extreme_runs.h"
#include "io/parameters.h"
#include "solvers/newton_solver.h"

#include <stdexcept>
#include <string>
#include <vector>

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  // Φ(u) = Σ u_i² with the residual's sign flipped: F = -2 u, J = 2 I.
  class ClimbingProblem : public NonlinearProblem
  {
  public:
    double
    objective(const TrilinosWrappers::MPI::Vector &u) override
    {
      return u.norm_sqr();
    }

    void
    residual(const TrilinosWrappers::MPI::Vector &u,
             TrilinosWrappers::MPI::Vector       &F) override
    {
      F = u;
      F *= -2.;
    }

    void
    tangent(const TrilinosWrappers::MPI::Vector &u,
            TrilinosWrappers::SparseMatrix      &J,
            const bool) override
    {
      for (const types::global_dof_index i : u.locally_owned_elements())
        J.set(i, i, 2.);
      J.compress(VectorOperation::insert);
    }
  };

  // Φ(u) = Σ u_i² + a jump of 1e3 where u_0 < 0.9999, from u_0 = 1: the exact Newton
  // step (J = 2 I) crosses the jump, and each search keeps less of it than the last.
  class StallingProblem : public ClimbingProblem
  {
  public:
    double
    objective(const TrilinosWrappers::MPI::Vector &u) override
    {
      return u.norm_sqr() + (u[0] < 0.9999 ? 1e3 : 0.);
    }

    void
    residual(const TrilinosWrappers::MPI::Vector &u,
             TrilinosWrappers::MPI::Vector       &F) override
    {
      F = u;
      F *= 2.;
    }

    // The index of the update's largest entry: Newton's update -u is largest at the
    // last unknown, u_9 = 10.
    std::string
    describe_update(const TrilinosWrappers::MPI::Vector &update) const override
    {
      unsigned int largest = 0;
      for (unsigned int i = 0; i < update.size(); ++i)
        if (std::abs(update[i]) > std::abs(update[largest]))
          largest = i;
      return "unknown " + std::to_string(largest);
    }
  };

  // Φ(u) = Σ u_i², F = 2 u, J = 2 I; the residual throws at its second evaluation.
  class DefectiveProblem : public ClimbingProblem
  {
  public:
    void
    residual(const TrilinosWrappers::MPI::Vector &u,
             TrilinosWrappers::MPI::Vector       &F) override
    {
      if (++evaluations == 2)
        throw std::logic_error("a planted defect");
      F = u;
      F *= 2.;
    }

    unsigned int evaluations = 0;
  };

  // Newton with the direct solver on `problem`, 10 unknowns from u_i = 1 + i.
  NewtonResult
  solve_small(NonlinearProblem &problem)
  {
    ParameterHandler prm;
    NonlinearSolverParameters::declare_parameters(prm);
    LinearSolverParameters::declare_parameters(prm);
    prm.enter_subsection("Linear solver");
    prm.set("Method", "direct");
    prm.leave_subsection();
    NonlinearSolverParameters nonlinear;
    LinearSolverParameters    linear;
    nonlinear.parse_parameters(prm);
    nonlinear.tangent = "adaptive"; // 'automatic' is resolved by Parameters only
    linear.parse_parameters(prm);

    const unsigned int n = 10;
    IndexSet           owned(n);
    owned.add_range(0, n);
    TrilinosWrappers::SparsityPattern sparsity(owned, MPI_COMM_SELF);
    for (unsigned int i = 0; i < n; ++i)
      sparsity.add(i, i);
    sparsity.compress();
    TrilinosWrappers::SparseMatrix matrix;
    matrix.reinit(sparsity);
    TrilinosWrappers::MPI::Vector u(owned, MPI_COMM_SELF);
    for (unsigned int i = 0; i < n; ++i)
      u[i] = 1. + i;

    std::ostringstream quiet;
    TimerOutput        timer(quiet, TimerOutput::never, TimerOutput::wall_times);
    NewtonSolver       newton(nonlinear, linear, NearNullSpace(), matrix, timer);
    return newton.solve(problem, u);
  }

  // Newton on `problem` must fail within `most` iterations, naming each of `causes`.
  unsigned int
  check_failure(ConditionalOStream             &pcout,
                const std::string              &name,
                NonlinearProblem               &problem,
                const unsigned int              most,
                const std::vector<std::string> &causes)
  {
    const NewtonResult result = solve_small(problem);
    pcout << name << ": converged " << result.converged << ", iterations "
          << result.iterations << ", failure \"" << result.failure << "\"" << std::endl;
    bool ok = !result.converged && result.iterations <= most;
    for (const std::string &cause : causes)
      ok &= result.failure.find(cause) != std::string::npos;
    if (!ok)
      {
        pcout << "  FAIL  expected a failure within " << most << " iterations naming";
        for (const std::string &cause : causes)
          pcout << " '" << cause << "'";
        pcout << std::endl;
      }
    return ok ? 0 : 1;
  }

  // 1c. The problem's exception must leave the solve unchanged.
  unsigned int
  check_defect(ConditionalOStream &pcout)
  {
    DefectiveProblem problem;
    std::string      what;
    try
      {
        const NewtonResult result = solve_small(problem);
        what = "none; the solve returned, converged " + std::to_string(result.converged) +
               ", failure \"" + result.failure + "\"";
      }
    catch (const std::logic_error &error)
      {
        what = error.what();
      }
    pcout << "1c. defective problem: the exception out of the solve: " << what
          << std::endl;
    if (what == "a planted defect")
      return 0;
    pcout << "  FAIL  expected the problem's own exception" << std::endl;
    return 1;
  }

  // 3. The scene's fraction (0.03) in the kinetic norm against the largest component:
  //    fewer Newton iterations, and the probes as close to the tight run.
  unsigned int
  check_kinetic_norm(ConditionalOStream             &pcout,
                     const std::string              &swing,
                     const std::filesystem::path    &root,
                     const std::vector<std::string> &common,
                     const SceneRun                 &tight,
                     const double                    step_difference)
  {
    const auto run = [&](const std::string &norm) {
      return run_scene(swing,
                       join(common,
                            {"Nonlinear solver/Truncation error fraction=0.03",
                             "Nonlinear solver/Truncation error norm=" + norm}),
                       (root / norm).string(),
                       MPI_COMM_WORLD);
    };
    const SceneRun largest = run("largest"), kinetic = run("kinetic");
    const double   ratio = static_cast<double>(kinetic.summary.newton_iterations) /
                         largest.summary.newton_iterations;
    double difference = 0.;
    for (const std::string probe : {"free_corner", "center"})
      difference = std::max(
        difference,
        (kinetic.probe_displacement(probe) - tight.probe_displacement(probe)).norm());
    pcout << "3. fraction 0.03: Newton iterations " << largest.summary.newton_iterations
          << " (largest component) and " << kinetic.summary.newton_iterations
          << " (kinetic norm): ratio " << ratio << "; the kinetic run's largest probe "
          << "difference to the tight run " << difference << " m" << std::endl;
    unsigned int failures = 0;
    if (!(ratio <= 0.95))
      {
        pcout << "  FAIL  the kinetic norm saves too few iterations" << std::endl;
        ++failures;
      }
    if (!(difference <= 0.25 * step_difference))
      {
        pcout << "  FAIL  the kinetic norm moved the probes by more than a quarter of "
                 "what halving the step does"
              << std::endl;
        ++failures;
      }
    return failures;
  }

  unsigned int
  check_truncation_error_fraction(ConditionalOStream &pcout)
  {
    namespace fs           = std::filesystem;
    const fs::path    root = scratch_directory("clothsim-newton-stopping");
    const std::string mesh =
      scratch_mesh(root / "mesh", {"swing-21.geo", "swing-grid.geo.inc"});
    // The tight runs: the fixed tolerance alone, whatever the scene sets.
    const std::vector<std::string> common = {
      "Mesh/Mesh file=" + mesh,
      "Time/End time=0.5",
      "Nonlinear solver/Displacement tolerance=1e-6",
      "Nonlinear solver/Truncation error fraction=0",
      "Nonlinear solver/Truncation error norm=largest"};
    const double      fraction = 0.1;
    const std::string swing    = source_path("params/benchmarks/swing.prm");
    const SceneRun    tight =
      run_scene(swing, common, (root / "tight").string(), MPI_COMM_WORLD);
    const SceneRun loose = run_scene(swing,
                                     join(common,
                                          {"Nonlinear solver/Truncation error fraction=" +
                                           std::to_string(fraction)}),
                                     (root / "loose").string(),
                                     MPI_COMM_WORLD);

    const double ratio = static_cast<double>(loose.summary.newton_iterations) /
                         tight.summary.newton_iterations;
    // The time discretisation's own effect: the tight run against one at dt/2.
    const SceneRun half =
      run_scene(swing,
                join(common, {"Time/Time step=" + std::to_string(1. / 120.)}),
                (root / "half").string(),
                MPI_COMM_WORLD);
    double solver_difference = 0., step_difference = 0.;
    for (const std::string probe : {"free_corner", "center"})
      {
        solver_difference = std::max(
          solver_difference,
          (loose.probe_displacement(probe) - tight.probe_displacement(probe)).norm());
        step_difference = std::max(
          step_difference,
          (half.probe_displacement(probe) - tight.probe_displacement(probe)).norm());
      }
    pcout << "2. swing N = 21, 0.5 s: Newton iterations "
          << tight.summary.newton_iterations << " (tolerance 1e-6 m) and "
          << loose.summary.newton_iterations << " (fraction " << fraction << "): ratio "
          << ratio << "; largest probe difference " << solver_difference
          << " m; the same run at dt/2 differs by " << step_difference << " m"
          << std::endl;
    unsigned int failures = 0;
    if (!(ratio <= 0.75))
      {
        pcout << "  FAIL  the fraction saves less than a quarter of the iterations"
              << std::endl;
        ++failures;
      }
    if (!(solver_difference <= 0.25 * step_difference))
      {
        pcout << "  FAIL  stopping early moved the probes by more than a quarter of "
                 "what halving the step does"
              << std::endl;
        ++failures;
      }
    return failures +
           check_kinetic_norm(pcout, swing, root, common, tight, step_difference);
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment        env(argc, argv);
  ClimbingProblem    climbing;
  StallingProblem    stalling;
  const unsigned int failures =
    check_failure(env.pcout, "1. climbing problem", climbing, 1, {"line search"}) +
    check_failure(env.pcout,
                  "1b. stalling problem",
                  stalling,
                  4,
                  {"stalled", "the last update's largest entry: unknown 9"}) +
    check_defect(env.pcout) + check_truncation_error_fraction(env.pcout);
  return finish(env.pcout, failures == 0);
}
