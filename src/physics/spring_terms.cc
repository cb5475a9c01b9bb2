#include "physics/spring_terms.h"

namespace clothsim::physics
{
  SpringTerm::SpringTerm(std::shared_ptr<const SpringNetwork> network)
    : GlobalTerm("springs", TermKind::elastic)
    , network(std::move(network))
  {}


  void
  SpringTerm::add_couplings(TrilinosWrappers::SparsityPattern &sparsity,
                            const AffineConstraints<double>   &constraints) const
  {
    network->add_sparsity(sparsity, constraints);
  }


  double
  SpringTerm::add_to_step(const VectorType                &u,
                          const StepTerms                 &step,
                          const AffineConstraints<double> &constraints,
                          VectorType                      *gradient,
                          MatrixType                      *hessian,
                          RankVector                      *dissipative_gradient) const
  {
    SpringNetwork::StepParts parts =
      damping != nullptr ? damping->step_parts(step) : SpringNetwork::StepParts();
    parts.elastic   = true;
    parts.projected = step.projected_tangent;
    return network->add_to_step(
      u, parts, constraints, gradient, hessian, dissipative_gradient);
  }


  double
  SpringTerm::energy(const VectorType &u,
                     const VectorType &v,
                     RankVector       *damping_force) const
  {
    if (damping_force != nullptr && damping != nullptr)
      return network->add_damping_force(v,
                                        damping->stiffness_proportional(),
                                        *damping_force,
                                        &u);
    return network->energy(u);
  }


  void
  SpringTerm::add_cell_fields(const mesh::Discretization &discretization,
                              const VectorType           &u,
                              std::vector<CellField>     &fields) const
  {
    CellField             strain{"spring_strain", {}};
    std::array<double, 9> u_e;
    for (const auto &element : discretization.elements())
      {
        const TrianglePositions x = discretization.current_positions(element, u, u_e);
        double                  largest = 0.;
        for (unsigned int i = 0; i < 3; ++i)
          {
            const unsigned int a = (i + 1) % 3, b = (i + 2) % 3;
            const double       edge_strain =
              (x[b] - x[a]).norm() /
                (element.reference[b] - element.reference[a]).norm() -
              1.;
            if (std::abs(edge_strain) > std::abs(largest))
              largest = edge_strain;
          }
        strain.values.push_back(largest);
      }
    fields.push_back(strain);
  }


  SpringDamping::SpringDamping(std::shared_ptr<SpringNetwork> network,
                               const double                   stiffness_proportional,
                               SpringTerm                    *springs)
    : GlobalTerm("spring damping", TermKind::dissipative)
    , network(std::move(network))
    , beta(stiffness_proportional)
    , springs(springs)
  {
    if (springs != nullptr)
      {
        AssertThrow(springs->network == this->network,
                    ExcMessage("the spring damping's host has other springs"));
        springs->damping = this;
      }
  }


  void
  SpringDamping::add_couplings(TrilinosWrappers::SparsityPattern &sparsity,
                               const AffineConstraints<double>   &constraints) const
  {
    network->add_sparsity(sparsity, constraints);
  }


  void
  SpringDamping::prepare_step(const VectorType &u_n)
  {
    network->prepare_damping(u_n);
  }


  SpringNetwork::StepParts
  SpringDamping::step_parts(const StepTerms &step) const
  {
    SpringNetwork::StepParts parts;
    parts.elastic = false;
    if (step.damping_weight > 0. && step.previous != nullptr)
      {
        parts.damping_coefficient = step.damping_weight * beta;
        parts.previous            = step.previous;
      }
    return parts;
  }


  double
  SpringDamping::energy(const VectorType &,
                        const VectorType &v,
                        RankVector       *damping_force) const
  {
    if (damping_force != nullptr)
      network->add_damping_force(v, beta, *damping_force);
    return 0.;
  }


  double
  SpringDamping::add_to_step(const VectorType                &u,
                             const StepTerms                 &step,
                             const AffineConstraints<double> &constraints,
                             VectorType                      *gradient,
                             MatrixType                      *hessian,
                             RankVector                      *dissipative_gradient) const
  {
    const SpringNetwork::StepParts parts = step_parts(step);
    if (parts.damping_coefficient == 0.)
      return 0.;
    return network->add_to_step(
      u, parts, constraints, gradient, hessian, dissipative_gradient);
  }
} // namespace clothsim::physics
