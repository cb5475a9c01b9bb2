#include "physics/damping.h"

#include "physics/inertia.h"

namespace clothsim::physics
{
  RayleighDamping::RayleighDamping(const mesh::Discretization &discretization,
                                   const double                mass_proportional,
                                   const double                stiffness_proportional,
                                   const double                areal_density,
                                   const bool                  lumped_mass,
                                   const MembraneTerm         *membrane)
    : discretization(discretization)
    , alpha(mass_proportional)
    , beta(membrane != nullptr ? stiffness_proportional : 0.)
    , areal_density(areal_density)
    , lumped_mass(lumped_mass)
    , membrane(membrane)
  {}


  void
  RayleighDamping::prepare_step(const VectorType &u_n)
  {
    if (beta == 0.)
      return;
    const auto &elements = discretization.elements();
    tangents.resize(elements.size());
    std::array<double, 9> u_e;
    for (unsigned int e = 0; e < elements.size(); ++e)
      membrane->projected_hessian(elements[e].reference,
                                  discretization.current_positions(elements[e], u_n, u_e),
                                  tangents[e]);
  }


  void
  RayleighDamping::add_to_step(const ElementState &element,
                               const StepTerms    &step,
                               double             &value,
                               LocalVector        *gradient,
                               LocalMatrix        *hessian) const
  {
    if (step.damping_weight == 0.)
      return;
    // s = u - u_n on the element.
    std::array<double, 9> s;
    for (unsigned int i = 0; i < 9; ++i)
      s[i] = element.u[i] - element.previous[i];

    // α part: w_d α/2 sᵀ M s.
    const double mass_weight = step.damping_weight * alpha;
    if (mass_weight > 0.)
      {
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
                  value += 0.5 * m_ab * (mass_weight * s[i] * s[j]);
                  if (gradient != nullptr)
                    (*gradient)[i] += m_ab * (mass_weight * s[j]);
                  if (hessian != nullptr)
                    (*hessian)[i][j] += mass_weight * m_ab;
                }
            }
      }

    // β part: w_d β/2 sᵀ K_n s.
    if (beta > 0.)
      {
        Assert(tangents.size() == discretization.elements().size(), ExcInternalError());
        const ElementMatrix &K = tangents[element.index];
        const double         c = step.damping_weight * beta;
        for (unsigned int i = 0; i < 9; ++i)
          {
            double Ks = 0.;
            for (unsigned int j = 0; j < 9; ++j)
              {
                Ks += K[i][j] * s[j];
                if (hessian != nullptr)
                  (*hessian)[i][j] += c * K[i][j];
              }
            if (gradient != nullptr)
              (*gradient)[i] += c * Ks;
            value += 0.5 * c * s[i] * Ks;
          }
      }
  }
} // namespace clothsim::physics
