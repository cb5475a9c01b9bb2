#pragma once

// The model of a scene: the list of terms it needs (physics/term.h), summed. One cell
// loop gathers each triangle's state once and lets every element term add to the same
// local gradient and Hessian; then every other term runs its own loop. A term that is
// not in the list costs nothing. Energies, output fields and the geometric checks of the
// steppers (area ratios) are evaluated here too.

#include "mesh/discretization.h"
#include "mesh/element_matrix_scatter.h"
#include "mesh/local_sums.h"
#include "physics/term.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace clothsim::physics
{
  // Energies at a state, J, summed over ranks: by kind, and per term (in the model's
  // term order).
  struct Energies
  {
    double              kinetic   = 0.;
    double              elastic   = 0.;
    double              potential = 0.; // gravity, pressure, loads: 0 at the reference
    std::vector<double> terms;
  };

  // A per-triangle output field (values in the order of the elements).
  struct CellField
  {
    std::string         name;
    std::vector<double> values;
  };

  class Model
  {
  public:
    // `constraints`: zero Newton updates at pinned and clamped dofs (kept by reference).
    Model(const mesh::Discretization      &discretization,
          const AffineConstraints<double> &constraints);

    void
    add(std::unique_ptr<ElementTerm> term);
    void
    add(std::unique_ptr<GlobalTerm> term);

    // Every term, element terms first, in the order added.
    const std::vector<Term *> &
    terms() const
    {
      return all_terms;
    }
    // The term called `name`, or null.
    const Term *
    find(const std::string &name) const;
    bool
    has_dissipation() const;

    // The tangent's sparsity: cells plus the couplings of the other terms.
    void
    initialize_matrix(MatrixType &matrix) const;

    // Φ(u) of the step (u ghosted; returned, summed over ranks); if non-null, its
    // gradient (owned, zero at constrained dofs) and Hessian (constrained rows and
    // columns eliminated, unit diagonal on the unused angle dofs), and the dissipative
    // terms' part of the gradient alone, rank-local (term.h; from the same loops: with
    // w_d = 1 and u_n = u - v it is the damping force (α M + β K_n) v of an explicit
    // step).
    double
    assemble(const VectorType &u,
             const StepTerms  &step,
             VectorType       *gradient,
             MatrixType       *hessian,
             RankVector       *dissipative_gradient = nullptr) const;

    // The dissipative terms' part of the gradient alone at u (ghosted) of the step
    // `step`, rank-local (term.h): a loop over them only, distributing nothing.
    void
    dissipative_gradient(const VectorType &u,
                         const StepTerms  &step,
                         RankVector       &gradient) const;

    // A rank-local vector (term.h) dotted with the ghosted vector `ghosted`, summed over
    // ranks: for a dissipative gradient and a step's displacement, the work done against
    // damping over the step, J.
    double
    work(const RankVector &force, const VectorType &ghosted) const;

    // The work done against the dissipative terms over a step: their gradient at the
    // solved iterate `u` (ghosted) of the step `step`, dotted with the step's
    // displacement `increment` (ghosted), J, summed over ranks.
    double
    dissipated_work(const VectorType &u,
                    const StepTerms  &step,
                    const VectorType &increment) const;

    // The elastic forces ∇W(u) of the elastic terms on every dof, constrained ones
    // included (u ghosted, `forces` owned).
    void
    elastic_forces(const VectorType &u, VectorType &forces) const;

    // The same for the static terms: elastic, loads (at `step`'s load factor and time)
    // and constraints (contact barriers), i.e. the force the supports must supply at
    // rest; no inertia, damping or friction.
    void
    static_forces(const VectorType &u, const StepTerms &step, VectorType &forces) const;

    // The gradient of the step's Φ at u (ghosted) with every term, constrained dofs
    // included (`forces` owned): at a pinned dof, the force the pin must exert on the
    // cloth for the step's equations to hold there.
    void
    step_forces(const VectorType &u, const StepTerms &step, VectorType &forces) const;

    // Energies at displacement u and velocity v (ghosted). If non-null,
    // `damping_force` gets the state's damping force D(u) v from the same loops (the
    // dissipative terms' gradient with w_d = 1 and u_n = u - v, K_n as last prepared;
    // rank-local, term.h).
    Energies
    energies(const VectorType &u,
             const VectorType &v,
             RankVector       *damping_force = nullptr) const;

    // Whether a term caps Newton's line search, and the largest step α <= 1 from u along
    // `direction` (both ghosted) that every term allows. Collective.
    bool
    caps_steps() const;
    double
    largest_step(const VectorType &u, const VectorType &direction) const;

    void
    prepare_step(const VectorType &u_n);
    void
    commit_step(const VectorType &u, VectorType &u_owned);

    // Smallest and largest current/reference area ratio over all triangles (collapse and
    // blow-up detection); a NaN gives (-1, infinity).
    std::pair<double, double>
    area_ratio_range(const VectorType &u) const;

    // Wall time spent in each term (in the order of terms()) by assemble() so far, s:
    // measured for the terms with their own loops, estimated for the element terms from
    // every 64th triangle (a clock read per term and triangle would cost as much as a
    // cheap term). A term that its host assembles (term.h) counts in the host's time.
    const std::vector<double> &
    term_seconds() const
    {
      return seconds;
    }

    // The term whose loop assembles terms()[k]: its host if the host is in the model
    // (term.h: GlobalTerm::host), else the term itself.
    const Term *
    assembled_by(const unsigned int k) const;

    // Per-triangle fields at u (ghosted): the Green strain norm sqrt(tr(M²)) and each
    // element term's own fields.
    std::vector<CellField>
    cell_fields(const VectorType &u) const;

  private:
    // Sets `forces` (owned) to the gradient of the terms of `kinds` at u (ghosted), no
    // constraints applied.
    void
    add_forces(const VectorType            &u,
               const StepTerms             &step,
               const std::vector<TermKind> &kinds,
               VectorType                  &forces) const;

    // Calls function(element state) for every locally owned triangle, with û and u_n
    // gathered only if given (else equal to u), the angles only with directors and the
    // positions at `linearised_from` only if given.
    template <class Function>
    void
    for_each_element(const VectorType &u,
                     const VectorType *predictor,
                     const VectorType *previous,
                     const Function   &function,
                     const VectorType *linearised_from = nullptr) const;

    const mesh::Discretization               &discretization;
    const AffineConstraints<double>          &constraints;
    std::vector<std::unique_ptr<ElementTerm>> element_terms;
    std::vector<std::unique_ptr<GlobalTerm>>  global_terms;
    std::vector<Term *>                       all_terms;
    std::vector<const Term *>                 assemblers; // per term, see assembled_by()
    bool                                      directors = false;
    unsigned int                              n_relevant_dofs; // of ghosted vectors
    std::vector<MembraneRestData>             rest; // per element, for strain and areas
    std::vector<types::global_dof_index> owned_unused_dofs; // unit diagonal in tangents
    mutable mesh::LocalSums              gradient_sums;     // the cell loop's gradient
    mutable mesh::ElementMatrixScatter   hessian_scatter;   // and its Hessian
    mutable std::vector<double>          seconds;         // per term, see term_seconds()
    const double                         timing_overhead; // s per sample
  };

  // Output fields of an element term (membrane stress, curvature change, ...).
  class FieldSource
  {
  public:
    virtual ~FieldSource() = default;
    // Appends this term's per-triangle fields at u (ghosted).
    virtual void
    add_cell_fields(const mesh::Discretization &discretization,
                    const VectorType           &u,
                    std::vector<CellField>     &fields) const = 0;
  };
} // namespace clothsim::physics
