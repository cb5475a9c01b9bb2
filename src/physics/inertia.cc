#include "physics/inertia.h"

namespace clothsim::physics
{
  InertiaTerm::InertiaTerm(const double areal_density, const bool lumped_mass)
    : ElementTerm("kinetic", TermKind::kinetic)
    , areal_density(areal_density)
    , lumped_mass(lumped_mass)
  {}


  void
  add_mass_quadratic(const bool                   lumped,
                     const double                 vertex_mass,
                     const double                 weight,
                     const std::array<double, 9> &u,
                     const std::array<double, 9> &centre,
                     double                      &value,
                     LocalVector                 *gradient,
                     LocalMatrix                 *hessian)
  {
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        {
          const double m_ab = mass_entry(lumped, vertex_mass, a, b);
          if (m_ab == 0.)
            continue;
          for (unsigned int d = 0; d < 3; ++d)
            {
              const unsigned int i = 3 * a + d, j = 3 * b + d;
              const double       r_i = u[i] - centre[i], r_j = u[j] - centre[j];
              value += 0.5 * m_ab * (weight * r_i * r_j);
              if (gradient != nullptr)
                (*gradient)[i] += m_ab * (weight * r_j);
              if (hessian != nullptr)
                (*hessian)[i][j] += weight * m_ab;
            }
        }
  }


  void
  InertiaTerm::add_to_step(const ElementState &element,
                           const StepTerms    &step,
                           double             &value,
                           LocalVector        *gradient,
                           LocalMatrix        *hessian) const
  {
    if (step.inertia_weight == 0.)
      return;
    add_mass_quadratic(lumped_mass,
                       areal_density * element.rest.area / 3.,
                       step.inertia_weight,
                       element.u,
                       element.predictor,
                       value,
                       gradient,
                       hessian);
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
