#pragma once

// Coulomb friction between the cloth and the obstacles, lagged once per step (Li et al.,
// "Incremental Potential Contact", 2020, sec. 5): for every vertex that started the step
// within the contact thickness, with the normal force λ and the tangent plane (t1, t2)
// taken at the step's start (ObstacleContact::begin_step), the dissipative potential
//   D = μ λ f0(|u_T|),   u_T = (t1, t2)ᵀ (x - c),
// where c is the vertex's start point carried along with the obstacle, so u_T is the
// slip relative to the obstacle's surface over the step; f0 (physics/contact_potential.h)
// turns static friction (slip below ε_v dt) smoothly into kinetic friction μ λ.

#include "physics/contact_term.h"

namespace clothsim::physics
{
  class ObstacleFriction : public GlobalTerm
  {
  public:
    // `contact`: the barrier term that lags the contacts (kept by reference).
    explicit ObstacleFriction(const ObstacleContact &contact);

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
    const ObstacleContact &contact;
  };
} // namespace clothsim::physics
