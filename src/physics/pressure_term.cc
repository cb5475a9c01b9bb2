#include "physics/pressure_term.h"

#include "physics/pressure.h"

namespace clothsim::physics
{
  PressureTerm::PressureTerm(const double pressure, const Point<3> &apex)
    : ElementTerm("pressure", TermKind::potential)
    , pressure(pressure)
    , apex(apex)
  {}


  void
  PressureTerm::add_to_step(const ElementState &element,
                            const StepTerms    &step,
                            double             &value,
                            LocalVector        *gradient,
                            LocalMatrix        *hessian) const
  {
    ElementVector g;
    ElementMatrix H;
    const bool    with_hessian = hessian != nullptr && !step.projected_tangent;
    const double  lambda       = step.load_factor;
    const double  potential    = pressure_potential_gradient_hessian(
      pressure, element.x, apex, g, with_hessian ? &H : nullptr);
    for (unsigned int i = 0; i < 9; ++i)
      {
        if (gradient != nullptr)
          (*gradient)[i] += lambda * g[i];
        if (with_hessian)
          for (unsigned int j = 0; j < 9; ++j)
            (*hessian)[i][j] += lambda * H[i][j];
      }
    value += lambda * potential;
  }


  double
  PressureTerm::energy(const ElementState &element, const std::array<double, 9> &) const
  {
    ElementVector g;
    return pressure_potential_gradient_hessian(pressure, element.x, apex, g, nullptr) -
           pressure_potential_gradient_hessian(
             pressure, element.reference, apex, g, nullptr);
  }
} // namespace clothsim::physics
