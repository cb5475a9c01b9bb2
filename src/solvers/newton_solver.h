#pragma once

// Newton's method through Trilinos NOX (line-search based, full Newton direction) on the
// Epetra objects of deal.II's TrilinosWrappers. A thin adapter: NOX asks for the residual
// F(u), the tangent J(u) and J⁻¹ F; the line search measures progress by the problem's
// objective (a user merit function), so each step minimises an incremental potential
// rather than
// ||F||² (Gast & Schroeder 2014). NOX's "Rescue Bad Newton Solve" is off: a failed linear
// solve fails the Newton solve, and the caller cuts the step. The variants: 'single step'
// takes one full linearised step and accepts it (Baraff & Witkin 1998); 'inexact newton'
// solves each linear system only to NOX's Eisenstat-Walker forcing term (Eisenstat &
// Walker 1996, choice 2); 'modified newton' keeps a tangent and its preconditioner for
// several iterations, across solves, as CVODE's Newton does (Hindmarsh et al. 2005).

#include <deal.II/base/timer.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include "io/parameters.h"
#include "solvers/linear_solver.h"

#include <limits>
#include <string>

namespace clothsim
{
  // What Newton needs from a problem. Vectors are locally owned (not ghosted).
  class NonlinearProblem
  {
  public:
    virtual ~NonlinearProblem() = default;

    // The objective whose gradient is the residual (J, summed over ranks).
    virtual double
    objective(const TrilinosWrappers::MPI::Vector &u) = 0;

    // F(u) = ∇objective, zero at constrained dofs.
    virtual void
    residual(const TrilinosWrappers::MPI::Vector &u,
             TrilinosWrappers::MPI::Vector       &F) = 0;

    // J(u) = ∇F, with constrained rows and columns eliminated; `projected`: a positive
    // definite modification instead of the exact Hessian.
    virtual void
    tangent(const TrilinosWrappers::MPI::Vector &u,
            TrilinosWrappers::SparseMatrix      &J,
            const bool                           projected) = 0;

    // From now on (until called with nullptr) an objective() or residual() at a new
    // point may assemble the tangent there too, into J (projected or not), and a
    // tangent() asked at that point finds it done. Full Newton's next tangent is at the
    // line search's accepted point, where the objective was just evaluated: one element
    // loop instead of two. J's content is the problem's from then on. The default does
    // not do it.
    virtual void
    speculate_tangents(TrilinosWrappers::SparseMatrix * /*J*/, bool /*projected*/)
    {}

    // The largest step α <= 1 along `direction` from u that the line search may try
    // (e.g. no contact crossed). Collective.
    virtual double
    largest_step(const TrilinosWrappers::MPI::Vector & /*u*/,
                 const TrilinosWrappers::MPI::Vector & /*direction*/)
    {
      return 1.;
    }

    // After the line search accepts an iterate u, before the residual there: the
    // problem may change itself (contact's adaptive barrier stiffness); returns whether
    // it did (then its objective and residual at u are taken again). Asked only if
    // adapts(). Collective.
    virtual bool
    adapts() const
    {
      return false;
    }
    virtual bool
    adapt(const TrilinosWrappers::MPI::Vector & /*u*/)
    {
      return false;
    }

    // For a failed solve's message: what the largest entry of a Newton update moves and
    // where (empty: nothing to add). Collective.
    virtual std::string
    describe_update(const TrilinosWrappers::MPI::Vector & /*update*/) const
    {
      return {};
    }

    // The size of a Newton update for the step-size convergence test: its largest
    // displacement component (m, over all ranks). The default takes every unknown.
    virtual double
    update_size(const TrilinosWrappers::MPI::Vector &update) const
    {
      return update.linfty_norm();
    }

    // A second test of a full update, which depends on the iterate u: the update's size
    // over what the problem tolerates at u, in the problem's own norm (converged below
    // 1; infinite: no such test). A time step compares it with a fraction of its
    // estimated truncation error at u.
    virtual double
    update_ratio(const TrilinosWrappers::MPI::Vector & /*update*/,
                 const TrilinosWrappers::MPI::Vector & /*u*/) const
    {
      return std::numeric_limits<double>::infinity();
    }
  };

  // A residual this many times the first iterate's (or the absolute tolerance, if
  // larger) has diverged: Newton and the arc-length corrector stop there.
  inline constexpr double divergence_factor = 1e10;

  struct NewtonResult
  {
    bool         converged         = false;
    unsigned int iterations        = 0;
    unsigned int linear_iterations = 0;  // summed over the Newton iterations
    double       residual_norm     = 0.; // ||F|| at the returned iterate, N
    unsigned int projected_fallbacks =
      0;                       // iterations that fell back to the projected tangent
    unsigned int tangents = 0; // tangents assembled (fewer than iterations if reused)
    std::string  failure;      // why it failed, if it did
  };

  class NewtonSolver
  {
  public:
    // `tangent_matrix` must have the problem's sparsity; it is used as NOX's Jacobian.
    NewtonSolver(const NonlinearSolverParameters &nonlinear,
                 const LinearSolverParameters    &linear,
                 NearNullSpace                    near_null_space,
                 TrilinosWrappers::SparseMatrix  &tangent_matrix,
                 TimerOutput                     &timer);

    // Solves F(u) = 0 starting from u (which satisfies the constraints); u gets the last
    // iterate. `minimum_displacement_tolerance` (m) raises 'Displacement tolerance' for
    // this solve (adaptive time steps: no effort below the time-error tolerance).
    NewtonResult
    solve(NonlinearProblem              &problem,
          TrilinosWrappers::MPI::Vector &u,
          const double                   minimum_displacement_tolerance = 0.);

    // The next solve computes a new tangent ('modified newton' reuses the last one
    // otherwise): call when the problem's tangent changed other than through u, e.g. a
    // new time step size. `rescaled`: it changed so much (a step size more than halved
    // or doubled) that the AMG hierarchy is built afresh rather than on old aggregates.
    void
    invalidate_tangent(const bool rescaled = false);

    // What a fresh solver would do next: a new tangent and a new AMG hierarchy, as
    // after a restart from a checkpoint (which stores neither). A run calls it after
    // writing a checkpoint, so that it goes on exactly as its restart does.
    void
    renew()
    {
      tangent_state = TangentState{};
      linear_solver.rebuild_next();
    }
    // MUMPS' choice of factorisation, which a checkpoint keeps (LinearSolver).
    bool
    definite_factorization() const
    {
      return linear_solver.definite_factorization();
    }
    void
    set_definite_factorization(const bool definite)
    {
      linear_solver.set_definite_factorization(definite);
    }
    // The tangent matrix's sparsity changed: the next solve analyses it afresh.
    void
    sparsity_changed()
    {
      tangent_state = TangentState{};
      linear_solver.sparsity_changed();
    }

    // What 'modified newton' carries from one iteration, and one solve, to the next.
    struct TangentState
    {
      bool         reusable               = false; // the matrix holds a usable tangent
      bool         preconditioner_current = false; // built for the matrix as it is
      bool         projected              = false; // the matrix is the projected one
      bool         refresh = false; // the last iteration converged too slowly
      unsigned int uses    = 0;     // iterations it has served
    };

  private:
    const NonlinearSolverParameters parameters;
    LinearSolver                    linear_solver;
    TrilinosWrappers::SparseMatrix &tangent_matrix;
    TimerOutput                    &timer;
    TangentState                    tangent_state;
  };
} // namespace clothsim
