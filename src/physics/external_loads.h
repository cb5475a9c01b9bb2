#pragma once

// Point, line and surface forces f_ext (N, fixed in direction and size: dead loads) and
// line moments (N·m on the shell's director angles ψ) as the potential -λ f_extᵀ u. The
// forces come assembled as a vector (zero at pinned dofs). The director angles restart
// from zero after every step (the directors are re-based, physics/bending_term.h), so a
// moment's share takes the rotation accumulated over the steps before as well:
// -λ m (ψ_acc + ψ), ψ_acc summed at every commit. statistics.csv reports the work the
// loads have done, f_extᵀ u with that total rotation, as `external_work`.

#include "physics/term.h"

namespace clothsim::physics
{
  class ExternalLoads : public GlobalTerm
  {
  public:
    // `forces`: owned vector of nodal forces, N (and moments, N·m, on angle dofs);
    // `angle_dofs`: the owned dofs that are director angles.
    ExternalLoads(const VectorType &forces, const IndexSet &angle_dofs);

    std::string
    report_column() const override
    {
      return "external_work";
    }
    double
    reported_value(const double energy) const override
    {
      return -energy;
    }

    double
    add_to_step(const VectorType                &u,
                const StepTerms                 &step,
                const AffineConstraints<double> &constraints,
                VectorType                      *gradient,
                MatrixType                      *hessian,
                RankVector                      *dissipative_gradient) const override;

    double
    energy(const VectorType &u,
           const VectorType &v,
           RankVector       *damping_force) const override;

    // ψ_acc += ψ of the step at u (before the angles are re-based).
    void
    commit_step(const VectorType &u, VectorType &u_owned) override;

    // ψ_acc of this rank's loaded angle dofs.
    std::vector<double>
    saved_state() const override
    {
      return accumulated;
    }
    void
    restore_state(const std::vector<double> &state) override;

  private:
    // f_extᵀ u over the locally owned dofs, the moments' rotations accumulated (J).
    double
    local_work(const VectorType &u) const;

    VectorType                           forces;
    std::vector<types::global_dof_index> loaded_dofs; // owned dofs with a force
    std::vector<double>                  loaded_values;
    // The loaded angle dofs (indices into loaded_dofs) and their accumulated rotation
    // ψ_acc, rad.
    std::vector<unsigned int> loaded_angles;
    std::vector<double>       accumulated;
  };
} // namespace clothsim::physics
