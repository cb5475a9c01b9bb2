#pragma once

// The mass-spring model's terms (physics/spring_network.h): the springs' energy
// Σ ½ k (ℓ - L)² in place of the membrane and bending elements, and their
// stiffness-proportional damping w_d β/2 sᵀ K_n s (K_n: the springs' projected Hessians
// at the step's start). Both loop over the springs, not over the cells; in a model with
// both, the springs' loop adds the damping too (SpringDamping::host), so that each
// spring's two parts are distributed once: the distribution dominates the loop's cost,
// and two loops made explicit damped runs 1.85 times slower.

#include "mesh/discretization.h"
#include "physics/model.h"
#include "physics/spring_network.h"

#include <memory>

namespace clothsim::physics
{
  class SpringDamping;

  class SpringTerm : public GlobalTerm, public FieldSource
  {
  public:
    explicit SpringTerm(std::shared_ptr<const SpringNetwork> network);


    void
    add_couplings(TrilinosWrappers::SparsityPattern &sparsity,
                  const AffineConstraints<double>   &constraints) const override;

    double
    add_to_step(const VectorType                &u,
                const StepTerms                 &step,
                const AffineConstraints<double> &constraints,
                VectorType                      *gradient,
                MatrixType                      *hessian,
                RankVector                      *dissipative_gradient) const override;

    // With `damping_force`: also the hosted damping's force, in the same loop.
    double
    energy(const VectorType &u,
           const VectorType &v,
           RankVector       *damping_force) const override;

    // spring_strain: per triangle, the strain (ℓ - L)/L of its edge with the largest
    // |strain| (the structural springs' strain).
    void
    add_cell_fields(const mesh::Discretization &discretization,
                    const VectorType           &u,
                    std::vector<CellField>     &fields) const override;

  private:
    friend class SpringDamping;

    std::shared_ptr<const SpringNetwork> network;
    const SpringDamping *damping = nullptr; // hosted: added in this term's loop
  };


  class SpringDamping : public GlobalTerm
  {
  public:
    // β in s. `springs` (may be null): the springs' term of the same network, whose loop
    // then adds this damping too (host()).
    SpringDamping(std::shared_ptr<SpringNetwork> network,
                  const double                   stiffness_proportional,
                  SpringTerm                    *springs = nullptr);

    const GlobalTerm *
    host() const override
    {
      return springs;
    }

    // β, s.
    double
    stiffness_proportional() const
    {
      return beta;
    }

    // The spring damping's part of a step: c = w_d β (0 without damping).
    SpringNetwork::StepParts
    step_parts(const StepTerms &step) const;

    // The springs' couplings (needed when the damping is alone).
    void
    add_couplings(TrilinosWrappers::SparsityPattern &sparsity,
                  const AffineConstraints<double>   &constraints) const override;

    std::string
    report_column() const override
    {
      return "damping_dissipated";
    }

    void
    prepare_step(const VectorType &u_n) override;

    double
    add_to_step(const VectorType                &u,
                const StepTerms                 &step,
                const AffineConstraints<double> &constraints,
                VectorType                      *gradient,
                MatrixType                      *hessian,
                RankVector                      *dissipative_gradient) const override;

    // No energy; with `damping_force`, its force β K_n v.
    double
    energy(const VectorType &u,
           const VectorType &v,
           RankVector       *damping_force) const override;

  private:
    std::shared_ptr<SpringNetwork> network;
    const double                   beta;
    const SpringTerm              *springs;
  };
} // namespace clothsim::physics
