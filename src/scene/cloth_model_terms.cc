// The terms of a scene's model, chosen from its parameters (the list is in
// scene/cloth_model.h): ClothModel::add_terms and add_self_contact.

#include <deal.II/base/mpi.h>

#include "io/input_error.h"
#include "physics/bending_term.h"
#include "physics/damping.h"
#include "physics/external_loads.h"
#include "physics/friction_term.h"
#include "physics/gravity.h"
#include "physics/inertia.h"
#include "physics/membrane_term.h"
#include "physics/pressure_term.h"
#include "physics/spring_terms.h"
#include "scene/air.h"
#include "scene/cloth_model.h"
#include "scene/group_loads.h"
#include "scene/obstacles.h"

#include <stdexcept>

namespace clothsim
{
  namespace
  {
    // make() builds a term from an orthotropic material (physics/sheet_stiffness.h),
    // which throws std::invalid_argument where the warp is normal to a triangle; on any
    // rank, that is an input error on every rank.
    template <typename Make>
    auto
    with_warp_checked(const MPI_Comm     communicator,
                      const std::string &parameter_file,
                      const Make        &make)
    {
      decltype(make()) term;
      std::string      problem;
      try
        {
          term = make();
        }
      catch (const std::invalid_argument &e)
        {
          problem = e.what();
        }
      if (Utilities::MPI::max(problem.empty() ? 0 : 1, communicator) > 0)
        throw InputError(parameter_file,
                         "Material/Warp direction",
                         problem.empty() ? "normal to a triangle of another rank"
                                         : problem);
      return term;
    }
  } // namespace


  void
  ClothModel::add_terms(const std::string &parameter_file, const mesh::MeshGroups &groups)
  {
    const MaterialParameters &material = parameters.material;
    const double              alpha    = parameters.damping.mass_proportional;
    const double              beta     = parameters.damping.stiffness_proportional;
    const bool                dynamic  = !is_static(parameters.time.integrator);
    const bool                fem      = parameters.scene.model == Model::fem;
    const double              rho      = material.areal_density;

    // Element terms, in one cell loop (this order is the order of summation).
    const physics::MembraneTerm *membrane = nullptr;
    if (fem)
      {
        physics::MembraneMaterial membrane_material{material.stretch_stiffness,
                                                    material.poisson_ratio};
        if (material.orthotropic)
          {
            membrane_material.weft_stretch_stiffness = material.weft_stretch_stiffness;
            membrane_material.shear_stiffness        = material.shear_stiffness;
            membrane_material.warp_direction         = material.warp_direction;
          }
        auto term =
          with_warp_checked(discretization.get_communicator(), parameter_file, [&]() {
            return std::make_unique<physics::MembraneTerm>(
              discretization, membrane_material, rho, material.lumped_mass, alpha);
          });
        membrane = term.get();
        model->add(std::move(term));
      }
    if (parameters.loads.gravity.norm() > 0.)
      model->add(std::make_unique<physics::GravityTerm>(rho, parameters.loads.gravity));
    if (dynamic)
      model->add(std::make_unique<physics::InertiaTerm>(rho, material.lumped_mass));
    if (dynamic && (alpha > 0. || (fem && beta > 0.)))
      model->add(std::make_unique<physics::RayleighDamping>(
        discretization, alpha, beta, rho, material.lumped_mass, membrane));
    // Air drag and wind (io/parameters.cc refuses it with a step it does not fit).
    if (dynamic && parameters.air.density > 0.)
      model->add(make_air_drag(parameters.air, parameter_file, discretization));
    // The pressure cones' apex: the reference surface's centroid.
    if (parameters.loads.pressure != 0.)
      model->add(
        std::make_unique<physics::PressureTerm>(parameters.loads.pressure,
                                                discretization.reference_centroid()));
    if (discretization.has_directors())
      {
        const physics::DirectorFunction function =
          material.director_function == "sine"      ? physics::DirectorFunction::sine
          : material.director_function == "tangent" ? physics::DirectorFunction::tangent
          : material.director_function == "half tangent"
            ? physics::DirectorFunction::half_tangent
            : physics::DirectorFunction::angle;
        physics::BendingMaterial bending{material.bending_rigidity,
                                         material.poisson_ratio,
                                         function};
        if (material.orthotropic)
          {
            bending.weft_rigidity  = material.weft_bending_rigidity;
            bending.warp_direction = material.warp_direction;
          }
        model->add(
          with_warp_checked(discretization.get_communicator(), parameter_file, [&]() {
            return std::make_unique<physics::BendingTerm>(
              discretization, bending, boundary_conditions->clamped_angles());
          }));
      }

    // Terms with their own loops.
    if (!fem)
      {
        const MassSpringParameters &given = parameters.mass_spring;
        const SpringConstants       constants{given.derived_constants,
                                        material.stretch_stiffness,
                                        material.poisson_ratio,
                                        material.bending,
                                        material.bending_rigidity,
                                        given.bend_reference_angle,
                                        given.structural_stiffness,
                                        given.shear_stiffness + given.bend_stiffness};
        VectorType                  prototype;
        discretization.initialize_ghosted(prototype);
        springs = std::make_shared<SpringNetwork>(discretization.get_dof_handler(),
                                                  constants,
                                                  prototype);
        // The springs' loop adds their damping too (one distribution per spring).
        auto spring_term = std::make_unique<physics::SpringTerm>(springs);
        std::unique_ptr<physics::SpringDamping> spring_damping;
        if (dynamic && beta > 0.)
          spring_damping =
            std::make_unique<physics::SpringDamping>(springs, beta, spring_term.get());
        model->add(std::move(spring_term));
        if (spring_damping)
          model->add(std::move(spring_damping));
      }
    if (has_group_loads(parameters.loads))
      model->add(std::make_unique<physics::ExternalLoads>(
        resolve_group_loads(discretization,
                            parameters.loads,
                            boundary_conditions->constraints(),
                            parameter_file,
                            groups),
        discretization.owned_angle_dofs()));

    // Contact with rigid obstacles: the barrier, and friction where μ > 0 (dynamic).
    const ContactParameters &given = parameters.contact;
    if (!given.obstacles.empty())
      {
        VectorType masses;
        lumped_masses(masses);
        physics::ContactSettings       settings  = contact_settings(given);
        std::vector<physics::Obstacle> obstacles = make_obstacles(given, parameter_file);
        settings.core_pairs_projected_exact =
          projected_exact_pairs(given, obstacles, parameters.time);
        auto term = std::make_unique<physics::ObstacleContact>(std::move(obstacles),
                                                               settings,
                                                               discretization,
                                                               masses);
        contact   = term.get();
        model->add(std::move(term));
        const bool friction = std::any_of(given.obstacles.begin(),
                                          given.obstacles.end(),
                                          [](const auto &o) { return o.friction > 0.; });
        if (dynamic && friction)
          model->add(std::make_unique<physics::ContactFriction>(*contact));
      }
    if (given.self_contact)
      add_self_contact(parameter_file);
  }


  void
  ClothModel::add_self_contact(const std::string &parameter_file)
  {
    const ContactParameters &given = parameters.contact;
    VectorType               masses, u, v, initial;
    lumped_masses(masses);
    initialize_owned(u);
    initialize_owned(v);
    initial_state(u, v);
    initialize_ghosted(initial);
    import_ghosts(u, initial);
    auto term = make_self_contact(given, parameter_file, discretization, masses, initial);
    self_contact = term.get();
    model->add(std::move(term));
    if (!is_static(parameters.time.integrator) && self_contact->has_friction())
      model->add(
        std::make_unique<physics::ContactFriction>(*self_contact, "self friction"));
  }
} // namespace clothsim
