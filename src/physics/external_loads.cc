#include "physics/external_loads.h"

namespace clothsim::physics
{
  ExternalLoads::ExternalLoads(const VectorType &forces)
    : GlobalTerm("external loads", TermKind::potential)
    , forces(forces)
  {
    for (const types::global_dof_index i : forces.locally_owned_elements())
      if (forces[i] != 0.)
        {
          loaded_dofs.push_back(i);
          loaded_values.push_back(forces[i]);
        }
  }


  double
  ExternalLoads::local_work(const VectorType &u) const
  {
    double work = 0.;
    for (const types::global_dof_index i : forces.locally_owned_elements())
      work += forces[i] * u[i];
    return work;
  }


  double
  ExternalLoads::add_to_step(const VectorType &u,
                             const StepTerms  &step,
                             const AffineConstraints<double> &,
                             VectorType *gradient,
                             MatrixType *,
                             RankVector *) const
  {
    if (gradient != nullptr)
      {
        std::vector<double> values(loaded_values);
        for (double &value : values)
          value *= -step.load_factor;
        gradient->add(loaded_dofs, values);
      }
    return -step.load_factor * local_work(u);
  }


  double
  ExternalLoads::energy(const VectorType &u, const VectorType &, RankVector *) const
  {
    return -local_work(u);
  }
} // namespace clothsim::physics
