#pragma once

// The inertia term of a step, w_i/2 (u - û)ᵀ M (u - û), with the mass matrix of P1
// triangles of areal density ρ (kg/m²), per displacement component:
//   lumped      M_ab = ρ|T̄|/3 δ_ab
//   consistent  M_ab = ρ|T̄|/12 (1 + δ_ab)
// Its energy in the report is the kinetic energy ½ vᵀ M v.

#include "physics/term.h"

namespace clothsim::physics
{
  // Entry (a, b) of the element mass matrix, with vertex_mass = ρ|T̄|/3 (kg).
  inline double
  mass_entry(const bool         lumped,
             const double       vertex_mass,
             const unsigned int a,
             const unsigned int b)
  {
    if (lumped)
      return a == b ? vertex_mass : 0.;
    return vertex_mass * (a == b ? 0.5 : 0.25);
  }

  // Adds weight/2 (u - c)ᵀ M (u - c) of one element to `value`, weight M (u - c) to
  // `gradient` and weight M to `hessian` (each may be null), with vertex_mass = ρ|T̄|/3.
  void
  add_mass_quadratic(const bool                   lumped,
                     const double                 vertex_mass,
                     const double                 weight,
                     const std::array<double, 9> &u,
                     const std::array<double, 9> &centre,
                     double                      &value,
                     LocalVector                 *gradient,
                     LocalMatrix                 *hessian);

  class InertiaTerm : public ElementTerm
  {
  public:
    InertiaTerm(const double areal_density, const bool lumped_mass);


    void
    add_to_step(const ElementState &element,
                const StepTerms    &step,
                double             &value,
                LocalVector        *gradient,
                LocalMatrix        *hessian) const override;

    double
    energy(const ElementState &element, const std::array<double, 9> &v_e) const override;

  private:
    const double areal_density;
    const bool   lumped_mass;
  };
} // namespace clothsim::physics
