#pragma once

// Point and line forces f_ext (N, fixed in direction and size: dead loads) as the
// potential -λ f_extᵀ u. The forces come assembled as a vector (zero at pinned dofs);
// statistics.csv reports the work they have done, λ f_extᵀ u, as `external_work`.

#include "physics/term.h"

namespace clothsim::physics
{
  class ExternalLoads : public GlobalTerm
  {
  public:
    // `forces`: owned vector of nodal forces, N.
    explicit ExternalLoads(const VectorType &forces);

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

  private:
    // f_extᵀ u over the locally owned dofs (J).
    double
    local_work(const VectorType &u) const;

    VectorType                           forces;
    std::vector<types::global_dof_index> loaded_dofs; // owned dofs with a force
    std::vector<double>                  loaded_values;
  };
} // namespace clothsim::physics
