#pragma once

// Pressure p (Pa) on the current surface as a potential, λ Φ_p(x) = -λ p V(x), V the
// volume of the cones from the reference surface's centroid c to the triangles (kernel
// and its closed-form derivatives in physics/pressure.h). Its Hessian is indefinite: the
// projected tangent leaves it out. Reported energy: -p (V(x) - V(X)), zero in the
// reference configuration like gravity's.

#include "physics/term.h"

namespace clothsim::physics
{
  class PressureTerm : public ElementTerm
  {
  public:
    // `apex`: the cones' apex c, m.
    PressureTerm(const double pressure, const Point<3> &apex);


    void
    add_to_step(const ElementState &element,
                const StepTerms    &step,
                double             &value,
                LocalVector        *gradient,
                LocalMatrix        *hessian) const override;

    double
    energy(const ElementState &element, const std::array<double, 9> &v_e) const override;

  private:
    const double   pressure;
    const Point<3> apex;
  };
} // namespace clothsim::physics
