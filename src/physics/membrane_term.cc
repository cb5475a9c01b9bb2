#include "physics/membrane_term.h"

#include <limits>

namespace clothsim::physics
{
  MembraneTerm::MembraneTerm(const mesh::Discretization &discretization,
                             const MembraneMaterial     &material,
                             const double                areal_density,
                             const bool                  lumped_mass,
                             const double                mass_proportional_damping)
    : ElementTerm("membrane", TermKind::elastic)
    , discretization(discretization)
    , areal_density(areal_density)
    , lumped_mass(lumped_mass)
    , mass_proportional_damping(mass_proportional_damping)
  {
    for (const auto &element : discretization.elements())
      {
        stiffness.push_back(membrane_stiffness(material,
                                               element.reference,
                                               membrane_rest_data(element.reference)));
      }
  }


  void
  MembraneTerm::add_to_step(const ElementState &element,
                            const StepTerms    &step,
                            double             &value,
                            LocalVector        *gradient,
                            LocalMatrix        *hessian) const
  {
    const MembraneRestData &rest = element.rest;
    if (gradient == nullptr && hessian == nullptr)
      {
        value += membrane_energy(stiffness[element.index], rest, element.x);
        return;
      }

    const double mass_weight =
      step.inertia_weight + step.damping_weight * mass_proportional_damping;
    const double  stress_floor = step.projected_tangent
                                   ? mass_weight * areal_density / (lumped_mass ? 9. : 36.)
                                   : std::numeric_limits<double>::infinity();
    ElementVector g;
    ElementMatrix H;
    value += membrane_energy_gradient_hessian(stiffness[element.index],
                                              rest,
                                              element.x,
                                              stress_floor,
                                              g,
                                              hessian != nullptr ? &H : nullptr,
                                              element.linearised_from);
    add_to_element(g, H, gradient, hessian);
  }


  double
  MembraneTerm::energy(const ElementState &element, const std::array<double, 9> &) const
  {
    return membrane_energy(stiffness[element.index], element.rest, element.x);
  }


  void
  MembraneTerm::projected_hessian(const unsigned int       element,
                                  const TrianglePositions &x,
                                  ElementMatrix           &hessian) const
  {
    ElementVector gradient;
    membrane_energy_gradient_hessian(stiffness[element],
                                     membrane_rest_data(
                                       discretization.elements()[element].reference),
                                     x,
                                     /*stress_floor=*/0.,
                                     gradient,
                                     &hessian);
  }


  void
  MembraneTerm::add_cell_fields(const mesh::Discretization &discretization,
                                const VectorType           &u,
                                std::vector<CellField>     &fields) const
  {
    CellField             stress{"membrane_stress", {}};
    std::array<double, 9> u_e;
    const auto           &elements = discretization.elements();
    for (unsigned int e = 0; e < elements.size(); ++e)
      stress.values.push_back(
        membrane_strain_stress(stiffness[e],
                               membrane_rest_data(elements[e].reference),
                               discretization.current_positions(elements[e], u, u_e))
          .stress_norm);
    fields.push_back(stress);
  }
} // namespace clothsim::physics
