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
    // r = u - c; the force weight M r and ½ rᵀ (weight M r), summed locally and added
    // once (a lumped M is diagonal).
    std::array<double, 9> r, force;
    for (unsigned int i = 0; i < 9; ++i)
      r[i] = u[i] - centre[i];
    if (lumped)
      for (unsigned int i = 0; i < 9; ++i)
        force[i] = vertex_mass * (weight * r[i]);
    else
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int d = 0; d < 3; ++d)
          {
            double sum = 0.;
            for (unsigned int b = 0; b < 3; ++b)
              sum += mass_entry(false, vertex_mass, a, b) * (weight * r[3 * b + d]);
            force[3 * a + d] = sum;
          }
    double quadratic = 0.;
    for (unsigned int i = 0; i < 9; ++i)
      quadratic += r[i] * force[i];
    value += 0.5 * quadratic;
    if (gradient != nullptr)
      for (unsigned int i = 0; i < 9; ++i)
        (*gradient)[i] += force[i];
    if (hessian != nullptr)
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          {
            const double m_ab = mass_entry(lumped, vertex_mass, a, b);
            if (m_ab == 0.)
              continue;
            for (unsigned int d = 0; d < 3; ++d)
              (*hessian)[3 * a + d][3 * b + d] += weight * m_ab;
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
        {
          const double m_ab = mass_entry(lumped_mass, vertex_mass, a, b);
          if (m_ab == 0.)
            continue;
          for (unsigned int d = 0; d < 3; ++d)
            kinetic += 0.5 * m_ab * v_e[3 * a + d] * v_e[3 * b + d];
        }
    return kinetic;
  }
} // namespace clothsim::physics
