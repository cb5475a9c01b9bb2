#pragma once

// The step's incremental potential as a sum of named terms (Gast & Schroeder, SCA 2014;
// backward Euler when w_i = 1/dt², w_d = 1/dt):
//   Φ(u) = w_i/2 (u - û)ᵀ M (u - û)                      inertia      (kinetic)
//        + W_membrane(u) + W_bending(u) + W_springs(u)   elastic terms
//        - λ f_gᵀ u + λ Φ_p(u) - λ f_extᵀ u              gravity, pressure, loads
//        + w_d/2 (u - u_n)ᵀ (α M + β K_n) (u - u_n)      Rayleigh damping (dissipative)
//        + Σ_T ψ_T(w_d (ū_T - ū_n,T) - w) / w_d          air drag (dissipative;
//                                                         physics/air_drag.h)
// Each term gives its value, gradient and Hessian (exact, or projected to positive
// semi-definite), and its energy at a state (u, v) for the run's energy budget. Element
// terms are sums over triangles and share one cell loop (physics/model.h); other terms
// (springs, point loads, contact pairs) bring their own loop over their candidates.

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include "physics/bending.h"
#include "physics/membrane.h"

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace clothsim
{
  using namespace dealii;

  using VectorType = TrilinosWrappers::MPI::Vector;
  using MatrixType = TrilinosWrappers::SparseMatrix;

  // Coefficients of one step's incremental potential (see physics/term.h).
  struct StepTerms
  {
    double            inertia_weight    = 0.;      // w_i, 1/s²
    double            damping_weight    = 0.;      // w_d, 1/s
    double            load_factor       = 1.;      // λ
    const VectorType *predictor         = nullptr; // û (ghosted); needed if w_i > 0
    const VectorType *previous          = nullptr; // u_n (ghosted); needed if w_d > 0
    bool              projected_tangent = true;    // Hessian: projected (PSD) or exact
    // With the mixed-stress tangent (physics/membrane.h): the state (ghosted) from which
    // the membrane's strain is linearised for the tangent's geometric stiffness; null:
    // the stress at u.
    const VectorType *linearised_from = nullptr;
    // The time of the state solved for (s; the load factor in static steps): where
    // moving obstacles are.
    double time = 0.;
  };
} // namespace clothsim

namespace clothsim::physics
{
  // What a term is, for the energy report: kinetic (½ vᵀ M v), elastic (stored strain
  // energy), potential (of the loads), dissipative (no stored energy: the stepper sums
  // the work done against it), constraint (barriers, penalties).
  enum class TermKind
  {
    kinetic,
    elastic,
    potential,
    dissipative,
    constraint
  };

  // This rank's contributions to a vector, on its locally relevant dofs in the order of
  // ghosted vectors (their local indices: Discretization::Element::local_dofs,
  // SpringNetwork::Entry::local_dofs), with no constraints applied and not summed over
  // ranks. Adding to it costs no global index lookup; its dot product with a ghosted
  // vector, summed over ranks, is the global one (Model::work). Used for the dissipative
  // terms' part of the gradient, the damping force of the energy budget.
  using RankVector = std::vector<double>;

  // 12 local unknowns of an element: x0, x1, x2 (9), then the edge angles ψ0, ψ1, ψ2.
  using LocalVector = BendingVector;
  using LocalMatrix = BendingMatrix;

  // Adds a kernel's gradient g and Hessian H over the first n local unknowns to the
  // element's sums (either may be null), each in a loop of its own (GCC's -O2 does not
  // hoist the tests out of a shared one).
  template <std::size_t n>
  void
  add_to_element(const std::array<double, n>                &g,
                 const std::array<std::array<double, n>, n> &H,
                 LocalVector                                *gradient,
                 LocalMatrix                                *hessian)
  {
    if (gradient != nullptr)
      for (std::size_t i = 0; i < n; ++i)
        (*gradient)[i] += g[i];
    if (hessian != nullptr)
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
          (*hessian)[i][j] += H[i][j];
  }

  // One triangle as the element terms see it in the cell loop.
  struct ElementState
  {
    unsigned int             index;     // in Discretization::elements()
    const TrianglePositions &reference; // X, m
    // The reference metric Ā, its inverse and the area |T̄| (physics/membrane.h).
    const MembraneRestData      &rest;
    const TrianglePositions     &x; // current positions, m
    const std::array<double, 9> &u; // displacements, m
    // û and u_n on the element (equal to u when the step has no such term).
    const std::array<double, 9> &predictor;
    const std::array<double, 9> &previous;
    // With directors: the element's edge angles ψ, rad (else unset).
    const EdgeAngles &psi;
    // Positions at StepTerms::linearised_from when a tangent is assembled, else null.
    const TrianglePositions *linearised_from = nullptr;
  };

  class Term
  {
  public:
    // `name`: short and lower-case ("membrane", "gravity"); statistics.csv gets a column
    // `<name>_energy` (spaces as underscores) unless the term names its own.
    Term(const std::string &name, const TermKind kind)
      : term_name(name)
      , term_kind(kind)
    {}
    virtual ~Term() = default;

    const std::string &
    name() const
    {
      return term_name;
    }
    TermKind
    kind() const
    {
      return term_kind;
    }

    // The column of statistics.csv that reports this term, and the value reported there
    // for the term's energy E (its contribution to the total).
    virtual std::string
    report_column() const;
    virtual double
    reported_value(const double energy) const
    {
      return energy;
    }

    // Before a step from u_n (ghosted): e.g. stiffness-proportional damping's K_n.
    virtual void
    prepare_step(const VectorType & /*u_n*/)
    {}

    // After a converged step at u (ghosted; `u_owned` may be changed, e.g. director
    // angles re-based to zero).
    virtual void
    commit_step(const VectorType & /*u*/, VectorType & /*u_owned*/)
    {}

    // What the term carries from one step to the next beyond the state vectors (this
    // rank's part; e.g. the shell's director references), for a checkpoint to restart
    // from; empty: nothing. restore_state takes back what saved_state gave, on the same
    // mesh and partition.
    virtual std::vector<double>
    saved_state() const
    {
      return {};
    }
    virtual void
    restore_state(const std::vector<double> & /*state*/)
    {}

    // Whether the term limits Newton's line search (a barrier whose argument must not
    // jump across it), and by how much: the largest α <= 1 from u along `direction` (both
    // ghosted), for this rank's part (Model::largest_step takes the minimum over ranks).
    virtual bool
    caps_steps() const
    {
      return false;
    }
    virtual double
    step_cap(const VectorType & /*u*/, const VectorType & /*direction*/) const
    {
      return 1.;
    }

    // Wall time (s, this rank) the term spent in its own named phases so far (e.g.
    // self-contact's broad phase, barrier and CCD), for the run's timing report.
    virtual std::vector<std::pair<std::string, double>>
    phase_seconds() const
    {
      return {};
    }

  private:
    const std::string term_name;
    const TermKind    term_kind;
  };

  // A term that is a sum over the triangles.
  class ElementTerm : public Term
  {
  public:
    using Term::Term;

    // Whether the term reads the director angles (then 12 local unknowns, else 9).
    virtual bool
    uses_directors() const
    {
      return false;
    }

    // Adds the element's part of Φ to `value`, and of its derivatives to `gradient` and
    // `hessian` (each may be null; entries 9..11 only if uses_directors()).
    virtual void
    add_to_step(const ElementState &element,
                const StepTerms    &step,
                double             &value,
                LocalVector        *gradient,
                LocalMatrix        *hessian) const = 0;

    // The element's energy at (u, v): v_e holds the element's velocities.
    virtual double
    energy(const ElementState &element, const std::array<double, 9> &v_e) const = 0;
  };

  // A term with its own loop (springs, point loads, contact pairs).
  class GlobalTerm : public Term
  {
  public:
    using Term::Term;

    // Couplings of dofs that share no cell.
    virtual void
    add_couplings(TrilinosWrappers::SparsityPattern & /*sparsity*/,
                  const AffineConstraints<double> & /*constraints*/) const
    {}

    // Adds this rank's part of Φ at u (ghosted; returned, not summed over ranks) to
    // `gradient` (owned) and `hessian` (each may be null), distributed through
    // `constraints`, not compressed. If non-null, `dissipative_gradient` (sized to the
    // relevant dofs) also gets the gradient of the dissipative terms this call adds (the
    // term itself if dissipative, and any it hosts) alone.
    virtual double
    add_to_step(const VectorType                &u,
                const StepTerms                 &step,
                const AffineConstraints<double> &constraints,
                VectorType                      *gradient,
                MatrixType                      *hessian,
                RankVector                      *dissipative_gradient) const = 0;

    // The term whose loop also adds this one (the springs' loop adds their damping: each
    // spring's parts summed and distributed once), or null. Model::assemble leaves a
    // term to its host when the host is in the model; alone (the dissipative terms'
    // gradient for the energy budget, a model without the host) it adds itself.
    virtual const GlobalTerm *
    host() const
    {
      return nullptr;
    }

    // This rank's part of the energy at (u, v) (ghosted). If non-null, `damping_force`
    // (sized to the relevant dofs) also gets the damping force at (u, v) of the
    // dissipative terms this call covers (the term itself if dissipative, and any it
    // hosts): their gradient with w_d = 1 and u_n = u - v, K_n as last prepared.
    virtual double
    energy(const VectorType &u, const VectorType &v, RankVector *damping_force) const = 0;
  };
} // namespace clothsim::physics
