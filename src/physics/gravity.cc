#include "physics/gravity.h"

namespace clothsim::physics
{
  GravityTerm::GravityTerm(const double areal_density, const Tensor<1, 3> &gravity)
    : ElementTerm("gravity", TermKind::potential)
    , areal_density(areal_density)
    , gravity(gravity)
  {}


  void
  GravityTerm::add_to_step(const ElementState &element,
                           const StepTerms    &step,
                           double             &value,
                           LocalVector        *gradient,
                           LocalMatrix *) const
  {
    const double vertex_mass = areal_density * element.rest.area / 3.;
    for (unsigned int v = 0; v < 3; ++v)
      for (unsigned int d = 0; d < 3; ++d)
        {
          const double load = step.load_factor * vertex_mass * gravity[d];
          value -= load * element.u[3 * v + d];
          if (gradient != nullptr)
            (*gradient)[3 * v + d] -= load;
        }
  }


  double
  GravityTerm::energy(const ElementState &element, const std::array<double, 9> &) const
  {
    const double vertex_mass = areal_density * element.rest.area / 3.;
    double       potential   = 0.;
    for (unsigned int v = 0; v < 3; ++v)
      for (unsigned int d = 0; d < 3; ++d)
        potential -= vertex_mass * gravity[d] * element.u[3 * v + d];
    return potential;
  }
} // namespace clothsim::physics
