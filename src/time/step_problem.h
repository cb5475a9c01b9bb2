#pragma once

// Newton's view of one implicit step: the step's incremental potential Φ (physics/term.h)
// from the model, its gradient and Hessian, with owned <-> ghosted copies.
//
// The average vector field (AVF) variant (Quispel & McLaren, J. Phys. A 41, 2008; for
// mechanics, Celledoni et al., J. Comput. Phys. 231, 2012) replaces the midpoint rule's
// force ∇W(x) at the midpoint x by its mean along the step's straight path,
//   ḡ(x) = ∫₀¹ ∇Φ(q_n + s (q₊ - q_n)) ds,   q₊ = 2x - q_n,
// so that W(q₊) - W(q_n) = ḡ·(q₊ - q_n) exactly: no energy is gained or lost by the
// elastic and load terms. ḡ is the gradient of
//   G(x) = ∫₀¹ (Φ(q_n + 2s (x - q_n)) - Φ(q_n)) / (2s) ds,
// with Hessian ∫₀¹ 2s ∇²Φ(q_n + 2s (x - q_n)) ds, so the step is still a minimisation
// with Newton's line search on G. Quadratic terms (inertia, Rayleigh damping) have
// their midpoint value: for them G(x) = Φ(x) - Φ(q_n), and the whole Φ can be averaged.
// Two-point Gauss quadrature, s = 1/2 ∓ √3/6, integrates G and ḡ exactly for the
// quartic St. Venant-Kirchhoff membrane and the linear loads (energy conserved to the
// Newton tolerance); for the bending term and the springs it is accurate to O(|Δq|⁴).

#include "solvers/newton_solver.h"
#include "time/model_interface.h"

#include <functional>
#include <limits>

namespace clothsim
{
  class StepProblem : public NonlinearProblem
  {
  public:
    // `timer` gets the "assemble energy", "assemble residual" and "assemble tangent"
    // sections.
    StepProblem(ModelInterface &model, const StepTerms &terms, TimerOutput &timer);

    // From now on the problem is the AVF step from the state `start` (owned, q_n) with
    // the midpoint x as unknown; `scratch` (the tangent's sparsity, or empty) holds one
    // node's Hessian while the other is assembled. Both are kept by reference.
    void
    average_along_path_from(const VectorType &start, MatrixType &scratch);

    // From now on every tangent takes the membrane's geometric stiffness from the strain
    // linearised from the point of the tangent before (physics/membrane.h, mixed-stress
    // tangent), the first from `start` (owned: the step's start u_n, where the AVF path's
    // points all begin too).
    void
    linearise_stress_from(const VectorType &start);

    double
    objective(const VectorType &u) override;

    void
    residual(const VectorType &u, VectorType &F) override;

    void
    tangent(const VectorType &u, MatrixType &J, const bool projected) override;

    // Not along the AVF path (two tangents per point). With contact the line search's
    // step cap keeps its points admissible, so Φ and the tangent there are finite.
    void
    speculate_tangents(MatrixType *J, bool projected) override;

    // The model's cap on the line search (contact), the obstacles at the step's time.
    double
    largest_step(const VectorType &u, const VectorType &direction) override;

    // Contact's adaptive barrier stiffness at an accepted iterate u (owned; contact
    // steps end on the state solved for, never the AVF's): Φ and its gradient are
    // assembled anew if it changed.
    bool
    adapts() const override
    {
      return model.adapts_stiffness();
    }
    bool
    adapt(const VectorType &u) override;

    // The largest update of a displacement dof (m).
    double
    update_size(const VectorType &update) const override;

    // The model's name for the update's largest entry.
    std::string
    describe_update(const VectorType &update) const override
    {
      return model.describe_largest_entry(update);
    }

    // The model changed under the same unknowns (friction lagged again at the solution):
    // Φ and its gradient are assembled anew, at the last point too.
    void
    forget_cached_values()
    {
      cached                  = false;
      tangent_at_cached_point = false;
    }

    // Newton's second step test: ratio(update, u), the update over what the step
    // tolerates at the iterate u.
    void
    set_update_ratio(std::function<double(const VectorType &, const VectorType &)> ratio)
    {
      iterate_ratio = std::move(ratio);
    }

    double
    update_ratio(const VectorType &update, const VectorType &u) const override
    {
      return iterate_ratio ? iterate_ratio(update, u)
                           : std::numeric_limits<double>::infinity();
    }

  private:
    // The tangent at `ghosted` (= x, owned), the evaluation point `node` (0, or the
    // AVF's 0 and 1).
    void
    assemble_tangent(unsigned int node, const VectorType &x, MatrixType &J);

    // Φ at u (owned) and its gradient into `gradient`, and the tangent there too if
    // speculate_tangents() asked; u becomes the cached point.
    double
    assemble_at(const VectorType &u, VectorType &gradient);

    // Whether x is not the last tangent's point of node `node` (mixed-stress tangent):
    // a tangent at x linearises from that point, else from the one before it.
    bool
    new_tangent_point(unsigned int node, const VectorType &x);

    // Whether objective() and residual() have Φ and its gradient at u (collective).
    bool
    at_cached_point(const VectorType &u) const;

    // ghosted = q_n + c (x - q_n), the path's point at the quadrature node's c = 2s.
    void
    set_path_point(const VectorType &x, const double c);

    std::function<double(const VectorType &, const VectorType &)> iterate_ratio;
    ModelInterface                                               &model;
    StepTerms                                                     terms;
    TimerOutput                                                  &timer;
    VectorType        ghosted, ghosted_direction;
    const VectorType *path_start = nullptr; // q_n (owned) of the AVF step, else null
    // Mixed-stress tangent: per evaluation point (the AVF's two nodes, else one) the
    // point of the last tangent and of the one before (owned; empty: off).
    std::vector<VectorType> tangent_points, earlier_tangent_points;
    VectorType              linearised_from, scratch; // ghosted, owned
    VectorType              owned_point, owned_sum;  // owned work vectors of the AVF step
    MatrixType             *first_tangent = nullptr; // the AVF tangent at the first node
    // Φ and its gradient come from one loop (model.assemble): the last point where
    // objective() or residual() assembled them (owned), and both, so that the other
    // call at the same point takes them instead of a loop of its own (NOX asks for the
    // residual at the line search's accepted iterate, and the line search for Φ at the
    // iterate whose residual NOX has).
    VectorType cached_point, cached_gradient;
    double     cached_energy = 0.;
    bool       cached        = false;
    // speculate_tangents(): the matrix, and whether it holds the tangent at the cached
    // point (not yet asked for).
    MatrixType *speculative_matrix      = nullptr;
    bool        speculative_projected   = false;
    bool        tangent_at_cached_point = false;
  };
} // namespace clothsim
