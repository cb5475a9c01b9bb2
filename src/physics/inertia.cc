#include "physics/inertia.h"

namespace clothsim::physics
{
  InertiaTerm::InertiaTerm(const double areal_density, const bool lumped_mass)
    : areal_density(areal_density)
    , lumped_mass(lumped_mass)
  {}


  void
  InertiaTerm::add_to_step(const ElementState &element,
                           const StepTerms    &step,
                           double             &value,
                           LocalVector        *gradient,
                           LocalMatrix        *hessian) const
  {
    const double w = step.inertia_weight;
    if (w == 0.)
      return;
    const double vertex_mass = areal_density * element.rest.area / 3.;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        {
          const double m_ab = mass_entry(lumped_mass, vertex_mass, a, b);
          if (m_ab == 0.)
            continue;
          for (unsigned int d = 0; d < 3; ++d)
            {
              const unsigned int i = 3 * a + d, j = 3 * b + d;
              const double       r_i = element.u[i] - element.predictor[i],
                           r_j       = element.u[j] - element.predictor[j];
              value += 0.5 * m_ab * (w * r_i * r_j);
              if (gradient != nullptr)
                (*gradient)[i] += m_ab * (w * r_j);
              if (hessian != nullptr)
                (*hessian)[i][j] += w * m_ab;
            }
        }
  }


  double
  InertiaTerm::energy(const ElementState &element, const std::array<double, 9> &v_e) const
  {
    const double vertex_mass = areal_density * element.rest.area / 3.;
    double       kinetic     = 0.;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        for (unsigned int d = 0; d < 3; ++d)
          kinetic += 0.5 * mass_entry(lumped_mass, vertex_mass, a, b) * v_e[3 * a + d] *
                     v_e[3 * b + d];
    return kinetic;
  }
} // namespace clothsim::physics
