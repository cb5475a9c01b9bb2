#include "physics/external_loads.h"

namespace clothsim::physics
{
  ExternalLoads::ExternalLoads(const VectorType &forces, const IndexSet &angle_dofs)
    : GlobalTerm("external loads", TermKind::potential)
    , forces(forces)
  {
    for (const types::global_dof_index i : forces.locally_owned_elements())
      if (forces[i] != 0.)
        {
          if (angle_dofs.is_element(i))
            loaded_angles.push_back(loaded_dofs.size());
          loaded_dofs.push_back(i);
          loaded_values.push_back(forces[i]);
        }
    accumulated.assign(loaded_angles.size(), 0.);
  }


  double
  ExternalLoads::local_work(const VectorType &u) const
  {
    double work = 0.;
    for (unsigned int k = 0; k < loaded_dofs.size(); ++k)
      work += loaded_values[k] * u[loaded_dofs[k]];
    for (unsigned int a = 0; a < loaded_angles.size(); ++a)
      work += loaded_values[loaded_angles[a]] * accumulated[a];
    return work;
  }


  void
  ExternalLoads::commit_step(const VectorType &u, VectorType &)
  {
    for (unsigned int a = 0; a < loaded_angles.size(); ++a)
      accumulated[a] += u[loaded_dofs[loaded_angles[a]]];
  }


  void
  ExternalLoads::restore_state(const std::vector<double> &state)
  {
    AssertThrow(state.size() == accumulated.size(),
                ExcMessage("the checkpoint's external loads do not fit this mesh"));
    accumulated = state;
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
