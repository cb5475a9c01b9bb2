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
    // Summed locally and added once (`value` and `gradient` may alias as far as the
    // compiler knows: per-entry updates of both cost as much as the rest of the term).
    const double vertex_mass = areal_density * element.rest.area / 3.;
    double       load[3];
    for (unsigned int d = 0; d < 3; ++d)
      load[d] = step.load_factor * vertex_mass * gravity[d];
    double work = 0.;
    for (unsigned int v = 0; v < 3; ++v)
      for (unsigned int d = 0; d < 3; ++d)
        work += load[d] * element.u[3 * v + d];
    value -= work;
    if (gradient != nullptr)
      for (unsigned int v = 0; v < 3; ++v)
        for (unsigned int d = 0; d < 3; ++d)
          (*gradient)[3 * v + d] -= load[d];
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
