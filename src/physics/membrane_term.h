#pragma once

// The membrane term: Σ_T W_T(x), the plane-stress St. Venant–Kirchhoff energy of the
// Green strain on every triangle (kernels in physics/membrane.h), with each triangle's
// constitutive tensor C^abcd (physics/sheet_stiffness.h) computed once. Its projected
// tangent keeps the compression of the geometric stiffness down to what the element's
// smallest mass eigenvalue m_min pays for in this step (ρ|T̄|/3 lumped, ρ|T̄|/12
// consistent, times the step's mass weight w_i + w_d α): s_min = weight m_min / (3|T̄|) =
// weight ρ/9 (lumped) or weight ρ/36 (consistent), so that the element Hessian plus its
// mass term stays positive semi-definite (membrane.h) and Newton stays exact wherever it
// can.

#include "physics/model.h"

namespace clothsim::physics
{
  class MembraneTerm : public ElementTerm, public FieldSource
  {
  public:
    // ρ (kg/m²), the lumping and α (1/s) set the stress floor of the projected tangent.
    // Throws std::invalid_argument for an orthotropic material whose warp is normal to
    // a triangle.
    MembraneTerm(const mesh::Discretization &discretization,
                 const MembraneMaterial     &material,
                 const double                areal_density,
                 const bool                  lumped_mass,
                 const double                mass_proportional_damping);


    void
    add_to_step(const ElementState &element,
                const StepTerms    &step,
                double             &value,
                LocalVector        *gradient,
                LocalMatrix        *hessian) const override;

    double
    energy(const ElementState &element, const std::array<double, 9> &v_e) const override;

    // Element `element`'s projected (tension-field) Hessian at positions x, N/m: the
    // stiffness of stiffness-proportional damping.
    void
    projected_hessian(const unsigned int       element,
                      const TrianglePositions &x,
                      ElementMatrix           &hessian) const;

    // membrane_stress: sqrt(tr((S Ā)²)) per triangle, N/m.
    void
    add_cell_fields(const mesh::Discretization &discretization,
                    const VectorType           &u,
                    std::vector<CellField>     &fields) const override;

  private:
    const mesh::Discretization    &discretization;
    const double                   areal_density;
    const bool                     lumped_mass;
    const double                   mass_proportional_damping;
    std::vector<MembraneStiffness> stiffness; // C^abcd per element
  };
} // namespace clothsim::physics
