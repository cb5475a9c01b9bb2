#pragma once

// What the time integrators need of a model, and all they know of it: vectors of its
// layout, the step's incremental potential (value, gradient, Hessian; physics/term.h),
// the pins' prescribed motion and the initial state, hooks before and after a step, the
// energy report, the state checks, and the fields to write. scene/ implements it.

#include <deal.II/lac/affine_constraints.h>

#include "io/checkpoint.h"
#include "io/output_writer.h"
#include "io/vtu_writer.h"
#include "physics/term.h"
#include "solvers/linear_solver.h"

#include <string>
#include <utility>
#include <vector>

namespace clothsim
{
  // Energies of a state for statistics.csv: by kind, and one value per reported column
  // (ModelInterface::energy_columns()), J.
  struct EnergyReport
  {
    double              kinetic   = 0.;
    double              elastic   = 0.;
    double              potential = 0.;
    std::vector<double> columns;
  };

  class ModelInterface
  {
  public:
    virtual ~ModelInterface() = default;

    virtual MPI_Comm
    get_communicator() const = 0;
    virtual const IndexSet &
    owned_dofs() const = 0;
    // The owned displacement dofs (no director angles): the error estimate's norm.
    virtual const IndexSet &
    displacement_dofs() const = 0;
    // Homogeneous constraints on pinned and clamped dofs (Newton updates there are 0).
    virtual const AffineConstraints<double> &
    get_constraints() const = 0;
    virtual void
    initialize_owned(VectorType &vector) const = 0;
    virtual void
    initialize_ghosted(VectorType &vector) const = 0;
    // ghosted = owned, for vectors made by the two functions above (faster than
    // deal.II's assignment on several ranks). Collective.
    virtual void
    import_ghosts(const VectorType &owned, VectorType &ghosted) const = 0;
    virtual void
    initialize_matrix(MatrixType &matrix) const = 0;
    virtual NearNullSpace
    near_null_space() const = 0;
    // The largest reference coordinate magnitude, m: the scale of round-off in the
    // positions X + u (Newton's round-off floor). Collective.
    virtual double
    reference_size() const = 0;
    // What the largest entry of `vector` (owned) moves and where, for a message (e.g. a
    // failed Newton solve's last update; mesh/largest_entry.h). Collective.
    virtual std::string
    describe_largest_entry(const VectorType & /*vector*/) const
    {
      return {};
    }
    // The lumped mass of every dof's vertex (owned, kg; zero on angle dofs).
    virtual void
    lumped_masses(VectorType &masses) const = 0;

    // The state at t = 0 (owned vectors), pins at their prescribed position.
    virtual void
    initial_state(VectorType &u, VectorType &v) const = 0;
    // Sets the pinned entries of `u` (owned) to the prescribed displacement at time t
    // (the load factor in static mode).
    virtual void
    apply_pinned_displacement(const double time, VectorType &u) const = 0;

    // Before a step from u_n (ghosted).
    virtual void
    prepare_step(const VectorType &u_n) = 0;
    // Φ(u) of the step (u ghosted; returned, summed over ranks); if non-null, its
    // gradient (owned, zero at constrained dofs) and Hessian.
    virtual double
    assemble(const VectorType &u,
             const StepTerms  &step,
             VectorType       *gradient,
             MatrixType       *hessian) const = 0;
    // Whether the model has contact (begin_step, relag_friction and largest_step do
    // something): they are then timed ("contact: ...").
    virtual bool
    has_contact() const = 0;
    // Whether largest_step can return less than one (contact, or a bending term with a
    // barrier): the line search then asks it ("line search: step cap" in the timer).
    virtual bool
    caps_steps() const = 0;
    // Before each attempt of a step from t_n to t_new, after the prediction (called if
    // caps_steps()): contact moves Newton's initial guess `u_new` (owned) off the
    // obstacles and lags friction from u_n (owned); a bending barrier pulls it back
    // towards u_n until no tilt on the path from u_n to u_n + path_end (u_new - u_n)
    // (the step's end: path_end = 2 when Newton solves for the midpoint) crosses it.
    // Collective. Returns why no feasible start exists (empty: found).
    virtual std::string
    begin_step(const double      t_n,
               const double      t_new,
               const VectorType &u_n,
               VectorType       &u_new,
               const double      path_end) = 0;
    // After begin_step, before Newton: whether the tangent's sparsity must be made again
    // (initialize_matrix) to hold the couplings the step from u_n to Newton's guess
    // u_new (owned) may need (self-contact pairs).
    virtual bool
    update_couplings(const VectorType & /*u_n*/, const VectorType & /*u_new*/)
    {
      return false;
    }
    // IPC's adaptive barrier stiffness (physics/barrier_stiffness.h): whether the model
    // has it, and at an iterate that Newton's line search accepted, right after Φ was
    // assembled there (the contact terms keep the closest distance they met), whether
    // a contact term raised its κ (Φ changed). Collective.
    virtual bool
    adapts_stiffness() const
    {
      return false;
    }
    virtual bool
    adapt_to_iterate()
    {
      return false;
    }
    // Friction solved further: its normal forces and tangent planes taken again at the
    // step's solution u (ghosted); returns their largest relative change (0 without
    // friction). Collective.
    virtual double
    relag_friction(const VectorType &u) = 0;
    // The largest step α <= 1 from u along `direction` (both ghosted) that Newton's
    // line search may take (contact: continuous collision detection against the
    // obstacles at `time`; bending: no tilt across its director function's barrier).
    // Collective.
    virtual double
    largest_step(const VectorType &u,
                 const VectorType &direction,
                 const double      time) const = 0;
    // After a converged step at u (ghosted); `u_owned` may change (director re-basing).
    virtual void
    commit_step(const VectorType &u, VectorType &u_owned) = 0;
    // The gradient of the step as assemble() gives it and, from the same loops, its
    // dissipative terms' part alone, rank-local (physics/term.h): with w_d = 1 and
    // u_n = u - v, the damping force D(u) v of an explicit step.
    virtual void
    assemble_gradient(const VectorType    &u,
                      const StepTerms     &step,
                      VectorType          &gradient,
                      physics::RankVector &dissipative_gradient) const = 0;
    // A rank-local vector dotted with a ghosted one, summed over ranks: the work of a
    // force over a displacement, J.
    virtual double
    work(const physics::RankVector &force, const VectorType &displacement) const = 0;
    // The work done against the dissipative terms over a step (see physics/model.h), J.
    virtual double
    dissipated_work(const VectorType &u,
                    const StepTerms  &step,
                    const VectorType &increment) const = 0;
    virtual bool
    has_dissipation() const = 0;
    // Whether the scene moves something it prescribes (Parameters::prescribes_motion());
    // then the steppers sum the work that motion does on the cloth (StepperCore::
    // add_prescribed_work), reported in the last of energy_columns(), "prescribed_work".
    virtual bool
    has_prescribed_motion() const = 0;
    // The gradient of the Φ of `step` at u (ghosted) with every term, constrained dofs
    // included (`forces` owned): at a pinned dof, the force the pin exerts on the cloth.
    virtual void
    step_forces(const VectorType &u, const StepTerms &step, VectorType &forces) const = 0;
    // The work done on the cloth by the obstacles' prescribed motion from t_n to t_new,
    // the cloth at u_n and u_new (ghosted), J (collective; physics/contact_term.h).
    virtual double
    obstacle_work(const VectorType &u_n,
                  const VectorType &u_new,
                  const double      t_n,
                  const double      t_new) const = 0;

    // Smallest and largest current/reference triangle area ratio at u (ghosted); NaN
    // gives (-1, infinity).
    virtual std::pair<double, double>
    area_ratio_range(const VectorType &u) const = 0;

    // Provot's strain limit after a dynamic step (u, v owned): whether the model has one,
    // and the springs still beyond it and their largest strain after the sweeps.
    virtual bool
    has_strain_limit() const = 0;
    virtual std::pair<types::global_dof_index, double>
    limit_strain(VectorType &u, VectorType &v, const double dt) const = 0;
    // The energy that the adaptive barrier stiffness's raises in a step added, at its end
    // u_new (ghosted) at t_new (physics/adaptive_barrier_term.h), J (collective); before
    // commit_step.
    virtual double
    stiffness_raise_energy(const VectorType &u_new, const double t_new) const = 0;
    // K + W + P at (u, v), ghosted, J (collective): the energy report's total alone.
    virtual double
    mechanical_energy(const VectorType &u, const VectorType &v) const = 0;

    // The names of the model's terms, and the statistics.csv columns that report them
    // beyond kinetic, elastic, potential and total energy.
    virtual std::vector<std::string>
    term_names() const = 0;
    virtual std::vector<std::string>
    energy_columns() const = 0;
    // Energies at (u, v), ghosted; `dissipated`: the work done against the dissipative
    // terms so far, J, reported in their column.
    virtual EnergyReport
    energies(const VectorType &u, const VectorType &v, const double dissipated) const = 0;
    // The same and, from the same loops, the state's damping force D(u) v (the
    // dissipative terms' gradient with w_d = 1 and u_n = u - v, K_n as last prepared;
    // rank-local, physics/term.h).
    virtual EnergyReport
    energies(const VectorType    &u,
             const VectorType    &v,
             const double         dissipated,
             physics::RankVector &damping_force) const = 0;

    // This rank's part of a checkpoint (io/checkpoint.h): what the terms carry from step
    // to step (physics::Term::saved_state) and a fingerprint of the mesh and partition.
    virtual void
    save_state(io::CheckpointData &rank) const = 0;
    // Takes it back on a restart; InputError (naming the checkpoint) if the fingerprint
    // differs: the mesh, its refinement or the partition is not the checkpoint's.
    virtual void
    restore_state(const io::CheckpointData &rank) = 0;

    // The fields of an output frame at (u, v), ghosted.
    virtual io::FrameData
    output_fields(const VectorType &u, const VectorType &v) const = 0;

    // Each support's reaction at u (ghosted) at `time` (the load factor in static
    // mode), the same on every rank; none by default. Collective.
    virtual std::vector<SupportReaction>
    support_reactions(const VectorType & /*u*/, const double /*time*/) const
    {
      return {};
    }
  };
} // namespace clothsim
