#pragma once

// Rayleigh damping as a dissipative term of the step (the damping force (α M + β K_n) v
// as the gradient of a quadratic):
//   w_d/2 (u - u_n)ᵀ (α M + β K_n) (u - u_n)
// with M the mass matrix (physics/inertia.h), K_n the membrane's projected tangent at the
// step's start (prepare_step), α in 1/s and β in s. With w_d = 1/dt its gradient is the
// damping force at the step's velocity (u - u_n)/dt. It stores no energy: the stepper
// sums the work done against it (statistics.csv: damping_dissipated).

#include "mesh/discretization.h"
#include "physics/membrane_term.h"

#include <vector>

namespace clothsim::physics
{
  class RayleighDamping : public ElementTerm
  {
  public:
    // `membrane`: the stiffness of the β part (null: no β part, e.g. with springs, which
    // damp themselves).
    RayleighDamping(const mesh::Discretization &discretization,
                    const double                mass_proportional,
                    const double                stiffness_proportional,
                    const double                areal_density,
                    const bool                  lumped_mass,
                    const MembraneTerm         *membrane);

    std::string
    report_column() const override
    {
      return "damping_dissipated";
    }

    void
    prepare_step(const VectorType &u_n) override;

    void
    add_to_step(const ElementState &element,
                const StepTerms    &step,
                double             &value,
                LocalVector        *gradient,
                LocalMatrix        *hessian) const override;

    double
    energy(const ElementState &, const std::array<double, 9> &) const override
    {
      return 0.;
    }

  private:
    const mesh::Discretization &discretization;
    const double                alpha, beta;
    const double                areal_density;
    const bool                  lumped_mass;
    const MembraneTerm         *membrane;
    std::vector<ElementMatrix>  tangents; // K_n per element, if β > 0
  };
} // namespace clothsim::physics
