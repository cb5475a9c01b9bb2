#pragma once

// What obstacle contact and self-contact share for IPC's adaptive barrier stiffness
// (physics/barrier_stiffness.h): a term whose barrier κ is scale × κ₀, the scale adapted
// to the closest pair each add_to_step meets.
// - begin_attempt, before each attempt of a step from u_n at t_n: the scale goes back to
//   the last accepted step's (what a failed or rejected attempt raised is taken back),
//   and the closest distance at u_n is recorded;
// - adapt_stiffness, at each iterate Newton's line search accepts (after add_to_step
//   there): may double the scale; returns whether it did;
// - commit_step keeps the scale for the next step; a checkpoint keeps it too;
// - raise_energy, before commit_step: the energy the raises of the step added at its
//   end, for the energy balance.
// All collective: the closest distance is the minimum over the ranks, so every rank
// decides the same.

#include "physics/barrier_stiffness.h"
#include "physics/term.h"

#include <deal.II/base/mpi.h>

#include <limits>
#include <string>
#include <vector>

namespace clothsim::physics
{
  class AdaptiveBarrierTerm : public GlobalTerm
  {
  public:
    AdaptiveBarrierTerm(const std::string       &name,
                        const StiffnessSettings &settings,
                        const MPI_Comm           communicator)
      : GlobalTerm(name, TermKind::constraint)
      , stiffness(settings)
      , communicator(communicator)
    {}

    // `u_n` ghosted.
    void
    begin_attempt(const VectorType &u_n, const double t_n)
    {
      if (!stiffness.adaptive())
        return;
      stiffness.begin_attempt(closest_at_start(u_n, t_n));
      scale_changed();
    }
    bool
    adapt_stiffness()
    {
      if (!stiffness.adaptive() ||
          !stiffness.observe(
            dealii::Utilities::MPI::min(assembled_closest, communicator)))
        return false;
      scale_changed();
      return true;
    }
    const AdaptiveStiffness &
    barrier_stiffness() const
    {
      return stiffness;
    }
    // The energy that raising the scale since the last commit added, taken at the step's
    // end u_new (ghosted) at t_new, J (collective): the barrier is linear in κ, so (1 -
    // committed/current) of its energy there at the current scale. The step's change of
    // barrier energy, B(u_new; κ_new) - B(u_n; κ_old), is this plus B(u_new; κ_old) -
    // B(u_n; κ_old), the motion under the old κ (whose obstacle part motion_work
    // takes). Both terms are energies of the state the step reached, which the solve
    // found with κ_new: bounded by it. Taken at the start instead, B(u_n; κ_new) is a
    // state the new κ never acted on, its pairs as close as the step began (a raise by
    // 4,096 there was 28 J on a 0.1 kg sheet, README "Output").
    double
    raise_energy(const VectorType &u_new, const double t_new) const
    {
      const double current = stiffness.scale(), committed = stiffness.committed_scale();
      if (current == committed) // the same on every rank
        return 0.;
      return (1. - committed / current) *
             dealii::Utilities::MPI::sum(barrier_energy(u_new, t_new), communicator);
    }

    void
    commit_step(const VectorType & /*u*/, VectorType & /*u_owned*/) override
    {
      stiffness.commit();
    }
    std::vector<double>
    saved_state() const override
    {
      return stiffness.saved();
    }
    void
    restore_state(const std::vector<double> &state) override
    {
      stiffness.restore(state);
      scale_changed();
    }

  protected:
    // This rank's part of the barrier's energy at u (ghosted), the obstacles at `time`.
    virtual double
    barrier_energy(const VectorType &u, const double time) const = 0;
    // The closest distance that counts at u_n (ghosted) at t_n (m, over all ranks; +inf
    // if none is near). Collective.
    virtual double
    closest_at_start(const VectorType &u_n, const double t_n) const = 0;
    // After the scale changed: e.g. passes it on to a part that keeps its own copy.
    virtual void
    scale_changed()
    {}

    AdaptiveStiffness stiffness; // κ / κ₀
    // The closest distance the last add_to_step met on this rank (m).
    mutable double assembled_closest = std::numeric_limits<double>::infinity();

  private:
    const MPI_Comm communicator;
  };
} // namespace clothsim::physics
