// Sections "Nonlinear solver" (Newton variants, tolerances, tangent) and "Linear
// solver" (Krylov method or direct solver, preconditioner).

#include "io/parameters.h"

#include <deal.II/base/parameter_handler.h>

namespace clothsim
{
  namespace
  {
    const char *const solver_methods = "cg|gmres|direct";
  } // namespace


  void
  NonlinearSolverParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    prm.declare_entry(
      "Method",
      "newton",
      Patterns::Selection("newton|single step|inexact newton|modified newton"),
      "'newton': Newton iterations with line search until the tolerances below "
      "hold, each linear solve to 'Linear solver/Relative tolerance'. "
      "'single step': one linearised Newton step per time step, taken in "
      "full and accepted without a convergence test (Baraff & Witkin 1998): "
      "cheap, but the step's equations are not solved (measure the error against "
      "'newton'). Static mode needs a method that converges. "
      "'inexact newton': as 'newton', but each linear solve stops at the "
      "Eisenstat-Walker forcing term eta_k = 0.9 (|F_k|/|F_k-1|)^1.5 (their "
      "choice 2, safeguarded; between the linear solver's tolerance and "
      "'Forcing term maximum'): loose far from the solution, tight near it; needs "
      "an iterative linear solver. 'modified newton': a tangent and its "
      "preconditioner (or factorisation) serve up to 'Jacobian reuse' Newton "
      "iterations, across time steps while the step size stays the same; a new "
      "one is computed when an iteration reduces the residual by less than half, "
      "when the line search cuts a step, or after a failed step. Converges "
      "linearly: the step tolerances then bound the error only roughly.");
    prm.declare_entry(
      "Jacobian reuse",
      "10",
      Patterns::Integer(1, 10000),
      "'modified newton': the most Newton iterations one tangent serves.");
    prm.declare_entry(
      "Forcing term maximum",
      "0.1",
      Patterns::Double(1e-16, 0.9),
      "'inexact newton': the loosest relative tolerance of a linear solve (the "
      "first iteration of every step uses it).");
    prm.declare_entry("Maximum iterations",
                      "25",
                      Patterns::Integer(1, 1000),
                      "Newton iterations per step before the step counts as failed.");
    prm.declare_entry("Absolute tolerance",
                      "1e-9",
                      Patterns::Double(0., 1e10),
                      "Converged when the residual's root mean square over the unknowns "
                      "(its 2-norm over the square root of their number, as NOX's "
                      "length-scaled norm; N) is below this, ...");
    prm.declare_entry(
      "Relative tolerance",
      "1e-8",
      Patterns::Double(0., 1.),
      "... or below this times the residual at the step's first iterate.");
    prm.declare_entry(
      "Line search",
      "energy",
      Patterns::Selection("energy|full step"),
      "'energy': backtracking until the step's incremental potential decreases "
      "enough (Armijo); below its round-off, until the residual decreases. "
      "'full step': no line search.");
    prm.declare_entry(
      "Displacement tolerance",
      "1e-6",
      Patterns::Double(0., 1e3),
      "... or when a full Newton step (not cut by the line search) moves no "
      "vertex coordinate by more than this (m; director angles do not count). 0 "
      "disables this criterion.");
    prm.declare_entry(
      "Truncation error fraction",
      "0.03",
      Patterns::Double(0., 1.),
      "... or, in a dynamic run, when a full Newton step moves no vertex "
      "coordinate by more than this fraction of the time step's estimated "
      "local truncation error at the new iterate (m; the estimate of 'Time/"
      "Adaptive time steps', computed for every step): iterating further "
      "changes the answer by less than the time discretisation does. 0: off; "
      "0.01 to 0.1 is customary (Hairer & Wanner, Solving ODEs II, IV.8). The "
      "default 0.03 is the folding sheet's (README, \"Folding cloth\"); tests of "
      "a time integrator's own accuracy set 0.");
    prm.declare_entry(
      "Truncation error norm",
      "largest",
      Patterns::Selection("largest|kinetic"),
      "The norm in which 'Truncation error fraction' compares the Newton update "
      "with the truncation error estimate: 'largest', the largest vertex "
      "coordinate of each; 'kinetic', the root mean square of each weighted by "
      "the lumped masses (the norm of the step's kinetic energy; Hairer & "
      "Wanner's error norms are root mean squares): a fold's last Newton updates "
      "move a few vertices, which the largest component counts as if all had moved.");
    prm.declare_entry(
      "Print iterations",
      "false",
      Patterns::Bool(),
      "Print NOX's residual norm, step length and update norm for every Newton "
      "iteration (for diagnosing convergence).");
    prm.declare_entry(
      "Tangent",
      "automatic",
      Patterns::Selection("automatic|adaptive|projected|exact"),
      "Compression makes the membrane Hessian indefinite. 'projected': the "
      "geometric stiffness keeps only as much compressive stress as the step's "
      "mass term pays for, so the tangent is positive definite and CG is valid "
      "(Newton converges linearly where the sheet is strongly compressed). "
      "'exact': the true Hessian (quadratic convergence; CG may break down, "
      "use 'gmres' or 'direct'). 'adaptive': the exact Hessian, replaced by the "
      "projected one for a Newton iteration whose linear solve fails or does "
      "not give a descent direction. 'automatic': 'projected' in a dynamic run "
      "(the exact tangent of a folding sheet sends Newton uphill: README, "
      "\"Folding cloth\"), 'adaptive' in a static one (no mass term to pay for "
      "compression; the run log says which).");
    prm.declare_entry(
      "Mixed stress tangent",
      "false",
      Patterns::Bool(),
      "The membrane's geometric stiffness in the tangent takes the stress of the "
      "strain linearised from the previous tangent's point (the step's start for "
      "the first), not the stress at the iterate: Newton on the mixed form of the "
      "membrane (Magisano, Leonetti & Garcea 2017). The residual and the solution "
      "are unchanged; a stiff membrane that turns within a step takes fewer Newton "
      "iterations (the swinging sheet: 7 to 14 % fewer).");
    prm.leave_subsection();
  }

  void
  NonlinearSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    const std::string method_name = prm.get("Method");
    method                    = method_name == "single step" ? NewtonMethod::single_step
                                : method_name == "inexact newton"  ? NewtonMethod::inexact
                                : method_name == "modified newton" ? NewtonMethod::modified
                                                                   : NewtonMethod::full;
    jacobian_reuse            = prm.get_integer("Jacobian reuse");
    forcing_term_maximum      = prm.get_double("Forcing term maximum");
    max_iterations            = prm.get_integer("Maximum iterations");
    absolute_tolerance        = prm.get_double("Absolute tolerance");
    relative_tolerance        = prm.get_double("Relative tolerance");
    line_search               = prm.get("Line search");
    displacement_tolerance    = prm.get_double("Displacement tolerance");
    truncation_error_fraction = prm.get_double("Truncation error fraction");
    truncation_error_norm     = prm.get("Truncation error norm");
    print_iterations          = prm.get_bool("Print iterations");
    tangent                   = prm.get("Tangent");
    mixed_stress_tangent      = prm.get_bool("Mixed stress tangent");
    prm.leave_subsection();
  }


  void
  LinearSolverParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    prm.declare_entry(
      "Method",
      "direct",
      Patterns::Selection(solver_methods),
      "Each Newton step's linear solve: 'direct' (a sparse factorisation, see "
      "'Direct solver'; the fastest on every shipped scene, 1.8 times CG's speed "
      "on the hanging sheet at 43,601 vertices and 45 times on a folding sheet "
      "at 1,681, in 1.2 times CG's memory: README, \"The defaults\"), or the "
      "Krylov methods 'cg' (needs the projected tangent) and 'gmres', "
      "preconditioned by 'Preconditioner'. The default was 'cg' until December 2026.");
    prm.declare_entry(
      "Direct solver",
      "mumps",
      Patterns::Selection("mumps|klu"),
      "Sparse direct solver behind 'Method = direct': 'mumps' (multifrontal "
      "symmetric LDLᵀ with PORD's nested-dissection ordering, distributed over the "
      "MPI ranks; fast on large meshes; on one rank a positive definite tangent is "
      "factorised by clothsim's own supernodal Cholesky in MUMPS' order, 2.2 to 2.5 "
      "times faster at 6,561 vertices) or 'klu' (LU through Amesos, serial, no "
      "fill-reducing ordering for 2D meshes; small systems).");
    prm.declare_entry(
      "Factor precision",
      "double",
      Patterns::Selection("double|single"),
      "Precision of MUMPS' factors ('Direct solver = mumps'): 'double', or "
      "'single', refined in double precision until the residual is below 'Relative "
      "tolerance' (each refinement step counts as one linear iteration). Single "
      "takes less time on large meshes (swinging sheet: factorisation 1.2 times "
      "faster at 6,561 vertices, 1.4 times at 103,041) and half the factors' memory.");
    prm.declare_entry(
      "Preconditioner",
      "amg",
      Patterns::Selection("amg|jacobi"),
      "'amg': ML smoothed-aggregation algebraic multigrid, its near-null space the "
      "three translations and, for a nearly planar sheet, the rotation about its "
      "normal; with shell bending inside the block factorisation of the tangent (the "
      "director angles by their diagonal, AMG on the displacements' Schur "
      "complement). 'jacobi': point Jacobi.");
    prm.declare_entry(
      "Relative tolerance",
      "1e-6",
      Patterns::Double(1e-16, 1.),
      "Krylov stopping criterion, relative to the Newton residual's 2-norm; also "
      "the refinement's with 'Factor precision = single'.");
    prm.declare_entry("Maximum iterations",
                      "2000",
                      Patterns::Integer(1, 1000000),
                      "Krylov iterations before the linear solve counts as failed.");
    prm.declare_entry(
      "AMG smoother sweeps",
      "2",
      Patterns::Integer(1, 20),
      "Smoother sweeps per multigrid level (the Chebyshev polynomial's degree; "
      "with 'AMG smoother = block gauss-seidel' the finest level's sweeps).");
    prm.declare_entry("AMG aggregation threshold",
                      "1e-4",
                      Patterns::Double(0., 1.),
                      "ML aggregation threshold (strength of connection).");
    prm.declare_entry(
      "AMG smoother range",
      "20",
      Patterns::Double(1.1, 1000.),
      "The Chebyshev smoother damps eigenvalues in [λ_max / range, λ_max] of "
      "each level (ML's 'smoother: Chebyshev alpha'). 20 keeps the CG iteration "
      "count flat under refinement on the hanging sheet; ML's usual 10 gives "
      "fewer iterations on coarse meshes and about 30 % more per refinement.");
    prm.declare_entry(
      "AMG smoother",
      "chebyshev",
      Patterns::Selection("chebyshev|block gauss-seidel"),
      "The finest level's smoother: 'chebyshev' (Chebyshev on the diagonal, see 'AMG "
      "smoother range'), or 'block gauss-seidel' (ML's symmetric Gauss-Seidel on each "
      "vertex's 3 x 3 block of displacements, 'AMG smoother sweeps' times; coarser "
      "levels keep Chebyshev). A bent or folded sheet is stiff along its surface and "
      "soft along its normal at every vertex, which the diagonal does not see: on the "
      "swinging sheet (CG to 1e-6, first 0.1 s) the blocks take 16 and 19 CG "
      "iterations per Newton iteration at 1,681 and 6,561 vertices against 54 and 86, "
      "membrane only 6.9 and 12.9 against 56 and 394 (6 to 8 times faster at 6,561; the "
      "direct solver is faster still). On the flat hanging sheet, in tension, they "
      "save a sixth of the iterations and take 1.4 to 1.9 times longer.");
    prm.declare_entry(
      "AMG coarse size",
      "2000",
      Patterns::Integer(10, 100000),
      "Largest multigrid level solved directly (Amesos KLU), in unknowns.");
    prm.declare_entry(
      "AMG reuse aggregates",
      "true",
      Patterns::Bool(),
      "Keep the multigrid aggregates and only recompute the hierarchy's operators "
      "for a new tangent (same sparsity), as long as CG needs at most 30 % more "
      "iterations than right after the aggregates were built; false rebuilds "
      "everything for every tangent.");
    prm.leave_subsection();
  }

  void
  LinearSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    method                    = prm.get("Method");
    direct_solver             = prm.get("Direct solver");
    factor_precision          = prm.get("Factor precision");
    preconditioner            = prm.get("Preconditioner");
    relative_tolerance        = prm.get_double("Relative tolerance");
    max_iterations            = prm.get_integer("Maximum iterations");
    amg_smoother_sweeps       = prm.get_integer("AMG smoother sweeps");
    amg_aggregation_threshold = prm.get_double("AMG aggregation threshold");
    amg_reuse_aggregates      = prm.get_bool("AMG reuse aggregates");
    amg_coarse_size           = prm.get_integer("AMG coarse size");
    amg_chebyshev_range       = prm.get_double("AMG smoother range");
    amg_smoother              = prm.get("AMG smoother");
    prm.leave_subsection();
  }
} // namespace clothsim
