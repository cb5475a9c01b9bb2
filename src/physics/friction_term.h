#pragma once

// Coulomb friction of the cloth on the obstacles and on itself, lagged once per step (Li
// et al., "Incremental Potential Contact", 2020, sec. 5): for every contact within the
// contact thickness at the step's start (a vertex near an analytic obstacle, a pair of
// primitives near a mesh obstacle), with the normal force λ and the tangent plane (t1,
// t2) taken there (ObstacleContact::begin_step), the dissipative potential
//   D = μ λ f0(|u_T|),   u_T = (t1, t2)ᵀ Σ_i w_i (x_i - c_i),
// over the contact's cloth vertices x_i with their weights w_i in its closest point (1
// for a vertex), c_i the start points carried along with the obstacle: u_T is the slip
// relative to the obstacle's surface over the step. f0 (physics/contact_potential.h)
// turns static friction (slip below ε_v dt) smoothly into kinetic friction μ λ.

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include "mesh/element_matrix_scatter.h"
#include "physics/contact_term.h"

#include <array>

#include <string>
#include <vector>

namespace clothsim::physics
{
  class ContactFriction : public GlobalTerm
  {
  public:
    // `contact`: the barrier term that lags the contacts (kept by reference); `name`:
    // the term's ("friction" with obstacles, "self friction" between layers).
    explicit ContactFriction(const LaggedContacts &contact,
                             const std::string    &name = "friction");

    std::string
    report_column() const override
    {
      return "damping_dissipated"; // the column of all dissipated work
    }

    double
    add_to_step(const VectorType                &u,
                const StepTerms                 &step,
                const AffineConstraints<double> &constraints,
                VectorType                      *gradient,
                MatrixType                      *hessian,
                RankVector                      *dissipative_gradient) const override;

    // No stored energy (the stepper sums the work done against friction).
    double
    energy(const VectorType &, const VectorType &, RankVector *) const override
    {
      return 0.;
    }

  private:
    // Adds the contact's gradient g and tangent H (over `dofs`; `hessian` may be null) in
    // the rows of the points this rank owns only (a contact between vertices of several
    // ranks).
    static void
    add_owned_rows(const LaggedContact                        &lagged,
                   const Vector<double>                       &g,
                   const FullMatrix<double>                   &H,
                   const std::vector<types::global_dof_index> &dofs,
                   const AffineConstraints<double>            &constraints,
                   VectorType                                 *gradient,
                   MatrixType                                 *hessian);

    const LaggedContacts &contact;
    // The tangents of contacts with 1, 2, 3 and 4 points, all of this rank, added by
    // position (element: the contact's index in the lagged list), found anew for each
    // list (lag_count).
    mutable std::array<mesh::ElementMatrixScatter, 4> scatters;
    mutable unsigned long                             scattered_lags = 0;
  };
} // namespace clothsim::physics
