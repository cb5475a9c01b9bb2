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
    : ElementTerm("damping", TermKind::dissipative)
    , discretization(discretization)
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
      membrane->projected_hessian(e,
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
    // α part: w_d α/2 sᵀ M s with s = u - u_n.
    const double mass_weight = step.damping_weight * alpha;
    if (mass_weight > 0.)
      add_mass_quadratic(lumped_mass,
                         areal_density * element.rest.area / 3.,
                         mass_weight,
                         element.u,
                         element.previous,
                         value,
                         gradient,
                         hessian);

    // β part: w_d β/2 sᵀ K_n s.
    if (beta > 0.)
      {
        std::array<double, 9> s;
        for (unsigned int i = 0; i < 9; ++i)
          s[i] = element.u[i] - element.previous[i];
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
