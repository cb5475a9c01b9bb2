#pragma once

// What a run models, composed from its parts: the discretization (mesh/discretization.h),
// the boundary conditions (scene/boundary_conditions.h) and the sum of the terms the
// scene needs (physics/model.h), chosen from the parameters:
//   membrane            Model = fem
//   bending             Model = fem with Material/Bending
//   springs             Model = mass-spring (in place of membrane and bending)
//   kinetic (inertia)   dynamic integrators
//   gravity             a non-zero Loads/Gravity
//   pressure            a non-zero Loads/Pressure
//   external loads      point or line forces
//   damping             α > 0, or β > 0 (FEM: β K of the membrane; springs: their own)
// It implements the integrators' view of a model (time/model_interface.h).

#include "io/parameters.h"
#include "mesh/discretization.h"
#include "mesh/gmsh_reader.h"
#include "mesh/largest_entry.h"
#include "physics/contact_term.h"
#include "physics/model.h"
#include "physics/self_contact.h"
#include "physics/self_intersections.h"
#include "physics/spring_network.h"
#include "scene/boundary_conditions.h"
#include "time/model_interface.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace clothsim
{
  class ClothModel : public ModelInterface
  {
  public:
    // Builds the distributed mesh from `serial_mesh` (the same on every rank), the
    // boundary conditions and the terms. Throws InputError (naming `parameter_file`) for
    // unknown groups and bad expressions.
    ClothModel(const MPI_Comm             communicator,
               const Parameters          &parameters,
               const std::string         &parameter_file,
               const Triangulation<2, 3> &serial_mesh,
               const mesh::MeshGroups    &groups);

    // The parts.
    const mesh::Discretization &
    get_discretization() const
    {
      return discretization;
    }
    double
    reference_size() const override
    {
      return discretization.largest_reference_coordinate();
    }
    std::string
    describe_largest_entry(const VectorType &vector) const override
    {
      return mesh::describe_largest_entry(discretization, vector);
    }
    const BoundaryConditions &
    get_boundary_conditions() const
    {
      return *boundary_conditions;
    }
    const physics::Model &
    get_physics() const
    {
      return *model;
    }
    const DoFHandler<2, 3> &
    get_dof_handler() const
    {
      return discretization.get_dof_handler();
    }
    types::global_dof_index
    n_dofs() const
    {
      return discretization.n_dofs();
    }
    unsigned int
    n_vertices() const
    {
      return discretization.n_vertices();
    }
    unsigned int
    n_pinned_dofs() const
    {
      return boundary_conditions->n_pinned_dofs();
    }
    bool
    has_bending() const
    {
      return discretization.has_directors();
    }
    bool
    uses_springs() const
    {
      return springs != nullptr;
    }
    // The springs (only with uses_springs()).
    const SpringNetwork &
    get_springs() const
    {
      Assert(springs != nullptr, ExcInternalError());
      return *springs;
    }
    double
    reference_area() const
    {
      return discretization.reference_area();
    }
    double
    total_mass() const // kg
    {
      return parameters.material.areal_density * reference_area();
    }

    // Internal (elastic) forces ∇W(u) on every dof, pinned ones included (owned vector):
    // at pinned dofs these are the reactions the pins exert, with opposite sign.
    void
    internal_forces(const VectorType &u, VectorType &forces) const;

    // A per-triangle field of the output at u (ghosted) by name, in the order of the
    // discretization's elements; empty if the model has no such field.
    std::vector<double>
    cell_field(const VectorType &u, const std::string &name) const;

    // The mesh piece of this rank for the VTK output.
    io::SurfacePiece
    output_piece() const;

    // ModelInterface.
    MPI_Comm
    get_communicator() const override
    {
      return discretization.get_communicator();
    }
    const IndexSet &
    owned_dofs() const override
    {
      return discretization.owned_dofs();
    }
    const IndexSet &
    displacement_dofs() const override
    {
      return discretization.owned_displacement_dofs();
    }
    const AffineConstraints<double> &
    get_constraints() const override
    {
      return boundary_conditions->constraints();
    }
    void
    initialize_owned(VectorType &vector) const override
    {
      discretization.initialize_owned(vector);
    }
    void
    initialize_ghosted(VectorType &vector) const override
    {
      discretization.initialize_ghosted(vector);
    }
    void
    import_ghosts(const VectorType &owned, VectorType &ghosted) const override
    {
      discretization.import_ghosts(owned, ghosted);
    }
    void
    initialize_matrix(MatrixType &matrix) const override
    {
      model->initialize_matrix(matrix);
    }
    NearNullSpace
    near_null_space() const override;
    void
    lumped_masses(VectorType &masses) const override;
    void
    initial_state(VectorType &u, VectorType &v) const override
    {
      boundary_conditions->initial_state(u, v);
    }
    void
    apply_pinned_displacement(const double time, VectorType &u) const override
    {
      boundary_conditions->apply_pinned_displacement(time, u);
    }
    void
    prepare_step(const VectorType &u_n) override
    {
      model->prepare_step(u_n);
    }
    double
    assemble(const VectorType &u,
             const StepTerms  &step,
             VectorType       *gradient,
             MatrixType       *hessian) const override
    {
      return model->assemble(u, step, gradient, hessian);
    }
    std::string
    begin_step(const double      t_n,
               const double      t_new,
               const VectorType &u_n,
               VectorType       &u_new,
               const double      path_end) override;
    // The obstacles' contact term, if the scene has obstacles.
    const physics::ObstacleContact *
    obstacle_contact() const
    {
      return contact;
    }

    bool
    has_contact() const override
    {
      return contact != nullptr || self_contact != nullptr;
    }
    bool
    update_couplings(const VectorType &u_n, const VectorType &u_new) override;
    bool
    adapts_stiffness() const override
    {
      return parameters.contact.adaptive_stiffness && has_contact();
    }
    bool
    adapt_to_iterate() override;
    double
    relag_friction(const VectorType &u) override
    {
      return contact != nullptr ? contact->relag_friction(u) : 0.;
    }
    bool
    caps_steps() const override
    {
      return contact != nullptr || model->caps_steps();
    }
    double
    largest_step(const VectorType &u,
                 const VectorType &direction,
                 const double      time) const override
    {
      const double alpha = model->caps_steps() ? model->largest_step(u, direction) : 1.;
      return contact != nullptr
               ? std::min(alpha, contact->largest_step(u, direction, time))
               : alpha;
    }
    void
    commit_step(const VectorType &u, VectorType &u_owned) override
    {
      model->commit_step(u, u_owned);
    }
    void
    assemble_gradient(const VectorType    &u,
                      const StepTerms     &step,
                      VectorType          &gradient,
                      physics::RankVector &dissipative_gradient) const override
    {
      model->assemble(u, step, &gradient, nullptr, &dissipative_gradient);
    }
    double
    work(const physics::RankVector &force, const VectorType &displacement) const override
    {
      return model->work(force, displacement);
    }
    double
    dissipated_work(const VectorType &u,
                    const StepTerms  &step,
                    const VectorType &increment) const override
    {
      return model->dissipated_work(u, step, increment);
    }
    bool
    has_dissipation() const override
    {
      return model->has_dissipation();
    }
    bool
    has_prescribed_motion() const override
    {
      return prescribed_motion;
    }
    void
    step_forces(const VectorType &u,
                const StepTerms  &step,
                VectorType       &forces) const override
    {
      model->step_forces(u, step, forces);
    }
    double
    obstacle_work(const VectorType &u_n,
                  const VectorType &u_new,
                  const double      t_n,
                  const double      t_new) const override
    {
      return contact != nullptr ? contact->motion_work(u_n, u_new, t_n, t_new) : 0.;
    }
    std::pair<double, double>
    area_ratio_range(const VectorType &u) const override
    {
      return model->area_ratio_range(u);
    }
    bool
    has_strain_limit() const override
    {
      return springs != nullptr && parameters.mass_spring.strain_limit > 0.;
    }
    std::pair<types::global_dof_index, double>
    limit_strain(VectorType &u, VectorType &v, const double dt) const override;
    double
    stiffness_raise_energy(const VectorType &u_new, const double t_new) const override
    {
      double energy = 0.;
      if (adapts_stiffness() && contact != nullptr)
        energy += contact->raise_energy(u_new, t_new);
      if (adapts_stiffness() && self_contact != nullptr)
        energy += self_contact->raise_energy(u_new, t_new);
      return energy;
    }
    double
    mechanical_energy(const VectorType &u, const VectorType &v) const override
    {
      const physics::Energies energies = model->energies(u, v);
      return energies.kinetic + energies.elastic + energies.potential;
    }
    std::vector<std::string>
    term_names() const override;
    std::vector<std::string>
    energy_columns() const override;
    EnergyReport
    energies(const VectorType &u,
             const VectorType &v,
             const double      dissipated) const override;
    EnergyReport
    energies(const VectorType    &u,
             const VectorType    &v,
             const double         dissipated,
             physics::RankVector &damping_force) const override;
    io::FrameData
    output_fields(const VectorType &u, const VectorType &v) const override;

    // Reaction of each pinned and clamped group: R = ∇Π_static at its pinned dofs (the
    // elastic, load and contact terms' gradient, which the pins balance; quasi-static:
    // no inertia, damping or friction), summed, and the moment about the group's
    // vertex centroid c, Σ (x_i - c) × R_i + Σ_e (∂Π/∂ψ_e) t_e over its held edges
    // (t_e the edge's current unit direction, about which ψ_e turns the director).
    std::vector<SupportReaction>
    support_reactions(const VectorType &u, const double time) const override;
    // (scene/cloth_model_checkpoint.cc)
    void
    save_state(io::CheckpointData &rank) const override;
    void
    restore_state(const io::CheckpointData &rank) override;

  private:
    // The mesh and partition as this rank holds them: MPI ranks, dofs (global, owned),
    // triangles and a hash of their dofs and reference corners.
    std::vector<double>
    fingerprint() const;

    // Chooses and adds the terms the scene needs.
    void
    add_terms(const std::string &parameter_file, const mesh::MeshGroups &groups);

    // The report of the model's energies, with the work `dissipated` in the dissipative
    // terms' column.
    EnergyReport
    report(const physics::Energies &energies, const double dissipated) const;
    // With 'Contact/Self contact': the term, after checking the mesh and the initial
    // state for it.
    void
    add_self_contact(const std::string &parameter_file);
    // `energies` with the contact columns (if the scene has obstacles) and the drape
    // columns (if asked for) filled in at u (ghosted).
    EnergyReport
    add_step_report(const VectorType &u, EnergyReport energies) const;
    // Every triangle of the mesh (current corners, vertex ids) on rank 0; empty on the
    // other ranks. Collective.
    std::vector<physics::MeshTriangle>
    triangles_on_root(const VectorType &u) const;

    const Parameters &parameters;
    // Parameters::prescribes_motion(), read once (it parses expressions; the steppers
    // ask every step).
    const bool                          prescribed_motion;
    mesh::Discretization                discretization;
    std::unique_ptr<BoundaryConditions> boundary_conditions;
    std::unique_ptr<physics::Model>     model;
    std::shared_ptr<SpringNetwork>      springs;           // Model = mass-spring
    physics::ObstacleContact           *contact = nullptr; // the model's, if obstacles
    physics::SelfContact *self_contact = nullptr; // the model's, with 'Self contact'
    // Inverse lumped masses (ghosted, 0 on pinned dofs), for the strain limit.
    VectorType inverse_masses;
    // This rank's triangles and their vertices' dofs, for the output.
    mesh::Discretization::SurfacePiece piece;
  };
} // namespace clothsim
