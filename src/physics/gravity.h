#pragma once

// Gravity as a potential: -λ f_gᵀ u with the lumped weight f_g = ρ|T̄|/3 g on each vertex
// of each triangle (exact for P1 elements under a uniform field). Zero in the reference
// configuration.

#include "physics/term.h"

namespace clothsim::physics
{
  class GravityTerm : public ElementTerm
  {
  public:
    // ρ in kg/m², g in m/s².
    GravityTerm(const double areal_density, const Tensor<1, 3> &gravity);


    void
    add_to_step(const ElementState &element,
                const StepTerms    &step,
                double             &value,
                LocalVector        *gradient,
                LocalMatrix        *hessian) const override;

    double
    energy(const ElementState &element, const std::array<double, 9> &v_e) const override;

  private:
    const double       areal_density;
    const Tensor<1, 3> gravity;
  };
} // namespace clothsim::physics
