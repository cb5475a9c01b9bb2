#pragma once

// The bending term of the midedge-director shell: Σ_T W_T(x, ψ) (kernels in
// physics/bending.h) on the positions and the edges' director angles. It owns the edges'
// reference vectors r_E (the director at ψ = 0): they start at the rest directors and,
// after each converged step, are re-based on the current directors while ψ is set to
// zero, so the angles stay small. Clamped edges keep ψ = 0 and their rest director.
// Its projected tangent is the Gauss–Newton part of the Hessian. A director function with
// a barrier caps Newton's line search so that no tilt jumps across it.

#include "mesh/discretization.h"
#include "physics/model.h"

#include <set>
#include <vector>

namespace clothsim::physics
{
  class BendingTerm : public ElementTerm, public FieldSource
  {
  public:
    // `clamped_angles`: the angle dofs of clamped edges.
    BendingTerm(const mesh::Discretization              &discretization,
                const BendingMaterial                   &material,
                const std::set<types::global_dof_index> &clamped_angles);

    bool
    uses_directors() const override
    {
      return true;
    }

    void
    add_to_step(const ElementState &element,
                const StepTerms    &step,
                double             &value,
                LocalVector        *gradient,
                LocalMatrix        *hessian) const override;

    double
    energy(const ElementState &element, const std::array<double, 9> &v_e) const override;

    // Every unclamped edge's reference vector becomes its current director (from u,
    // ghosted), and the angles in `u_owned` become zero. (Angle rates stay: relative to
    // the new references they still predict the next step's rotation.)
    void
    commit_step(const VectorType &u, VectorType &u_owned) override;

    // The edges' reference vectors r_E (3 numbers per edge slot).
    std::vector<double>
    saved_state() const override;
    void
    restore_state(const std::vector<double> &state) override;

    // With a barrier in the director function ('tangent', 'half tangent'): no Newton
    // update may carry a tilt across it (tilt_step_bound on every triangle).
    bool
    caps_steps() const override
    {
      return barrier_tilt(material.director_function) > 0.;
    }
    double
    step_cap(const VectorType &u, const VectorType &direction) const override;

    // curvature_change: |Ā⁻¹(b - B̄)| per triangle, 1/m.
    void
    add_cell_fields(const mesh::Discretization &discretization,
                    const VectorType           &u,
                    std::vector<CellField>     &fields) const override;

  private:
    // The element's edge directors: reference vectors and signs.
    EdgeDirectors
    directors(const unsigned int element) const;

    const mesh::Discretization  &discretization;
    const BendingMaterial        material;
    std::vector<Tensor<1, 3>>    references; // r_E per edge slot
    std::vector<bool>            clamped;    // per edge slot
    std::vector<BendingRestData> rest;       // per element
  };
} // namespace clothsim::physics
