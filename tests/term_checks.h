#pragma once

// Checks of a model's step potential for tests/model_terms.cc: deterministic states,
// central differences of Φ and ∇Φ against ∇Φ·d and H d, and models of a single term
// with the parameters that scene/cloth_model.cc gives it.

#include "physics/bending_term.h"
#include "physics/damping.h"
#include "physics/external_loads.h"
#include "physics/gravity.h"
#include "physics/inertia.h"
#include "physics/membrane_term.h"
#include "physics/pressure_term.h"
#include "physics/spring_terms.h"
#include "scene/group_loads.h"
#include "test_support.h"

#include <memory>
#include <string>
#include <vector>

namespace clothsim::test
{
  // Deterministic values per dof (independent of the number of ranks), zero at the
  // constrained dofs: `displacement` (m) on displacement dofs, `angle` (rad) on angles.
  inline void
  fill(const ClothModel &model,
       VectorType       &vector,
       const double      displacement,
       const double      angle,
       const int         seed)
  {
    for (const auto i : model.owned_dofs())
      vector[i] = model.get_constraints().is_constrained(i)
                    ? 0.
                    : (model.displacement_dofs().is_element(i) ? displacement : angle) *
                        std::sin(0.37 * double(i) * seed + seed);
    vector.compress(VectorOperation::insert);
  }

  // Central differences of Φ and ∇Φ along d at u against ∇Φ·d and H d.
  struct Derivatives
  {
    double value;          // Φ(u)
    double directional;    // ∇Φ·d
    double curvature;      // d·H d
    double hd_norm;        // |H d|
    double gradient_error; // relative
    double hessian_error;  // relative (0 if H d and its difference are both zero)
  };

  // `assembled`: a ClothModel or a physics::Model on `layout`'s dofs.
  template <class Assembled>
  Derivatives
  derivatives(const Assembled  &assembled,
              const ClothModel &layout,
              const StepTerms  &terms,
              const VectorType &u,
              const VectorType &d,
              const double      h)
  {
    VectorType ghosted, gradient, g_plus, g_minus, Hd;
    layout.initialize_ghosted(ghosted);
    for (VectorType *vector : {&gradient, &g_plus, &g_minus, &Hd})
      layout.initialize_owned(*vector);
    MatrixType hessian;
    assembled.initialize_matrix(hessian);

    Derivatives result;
    ghosted      = u;
    result.value = assembled.assemble(ghosted, terms, &gradient, &hessian);
    hessian.vmult(Hd, d);

    VectorType shifted(u);
    shifted.add(h, d);
    ghosted               = shifted;
    const double phi_plus = assembled.assemble(ghosted, terms, &g_plus, nullptr);
    shifted.add(-2. * h, d);
    ghosted                = shifted;
    const double phi_minus = assembled.assemble(ghosted, terms, &g_minus, nullptr);

    result.directional               = gradient * d;
    result.curvature                 = d * Hd;
    result.hd_norm                   = Hd.l2_norm();
    const double difference_quotient = (phi_plus - phi_minus) / (2. * h);
    result.gradient_error =
      std::abs(difference_quotient - result.directional) /
      std::max(std::abs(result.directional), std::abs(difference_quotient));
    VectorType difference(g_plus);
    difference -= g_minus;
    difference /= 2. * h;
    const double fd_norm = difference.l2_norm();
    difference -= Hd;
    const double scale   = std::max(result.hd_norm, fd_norm);
    result.hessian_error = scale > 0. ? difference.l2_norm() / scale : 0.;
    return result;
  }

  // A model of the single term `name` of the FEM scene, on its mesh and constraints,
  // with the parameters scene/cloth_model.cc gives it. `membrane` keeps the stiffness of
  // the damping's β part alive.
  inline std::unique_ptr<physics::Model>
  single_term_model(const Scene                            &scene,
                    const std::string                      &parameter_file,
                    const std::string                      &name,
                    std::unique_ptr<physics::MembraneTerm> &membrane)
  {
    const Parameters           &parameters = scene.parameters();
    const MaterialParameters   &material   = parameters.material;
    const ClothModel           &model      = *scene.model;
    const mesh::Discretization &mesh       = model.get_discretization();
    auto result = std::make_unique<physics::Model>(mesh, model.get_constraints());
    const physics::MembraneMaterial membrane_material{material.stretch_stiffness,
                                                      material.poisson_ratio};
    const double                    rho   = material.areal_density;
    const double                    alpha = parameters.damping.mass_proportional;
    if (name == "membrane")
      result->add(std::make_unique<physics::MembraneTerm>(
        mesh, membrane_material, rho, material.lumped_mass, alpha));
    else if (name == "gravity")
      result->add(std::make_unique<physics::GravityTerm>(rho, parameters.loads.gravity));
    else if (name == "kinetic")
      result->add(std::make_unique<physics::InertiaTerm>(rho, material.lumped_mass));
    else if (name == "damping")
      {
        membrane = std::make_unique<physics::MembraneTerm>(
          mesh, membrane_material, rho, material.lumped_mass, alpha);
        result->add(std::make_unique<physics::RayleighDamping>(
          mesh,
          alpha,
          parameters.damping.stiffness_proportional,
          rho,
          material.lumped_mass,
          membrane.get()));
      }
    else if (name == "pressure")
      result->add(std::make_unique<physics::PressureTerm>(parameters.loads.pressure,
                                                          mesh.reference_centroid()));
    else if (name == "bending")
      {
        AssertThrow(material.director_function == "angle", ExcNotImplemented());
        result->add(std::make_unique<physics::BendingTerm>(
          mesh,
          physics::BendingMaterial{material.bending_rigidity,
                                   material.poisson_ratio,
                                   physics::DirectorFunction::angle},
          model.get_boundary_conditions().clamped_angles()));
      }
    else if (name == "external loads")
      result->add(std::make_unique<physics::ExternalLoads>(
        resolve_group_loads(
          mesh, parameters.loads, model.get_constraints(), parameter_file, scene.groups),
        mesh.owned_angle_dofs()));
    else if (name == "springs" || name == "spring damping")
      {
        // Springs of their own (as scene/cloth_model.cc makes them), each term with its
        // own loop.
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
        mesh.initialize_ghosted(prototype);
        auto springs =
          std::make_shared<SpringNetwork>(mesh.get_dof_handler(), constants, prototype);
        if (name == "springs")
          result->add(std::make_unique<physics::SpringTerm>(springs));
        else
          result->add(std::make_unique<physics::SpringDamping>(
            springs, parameters.damping.stiffness_proportional));
      }
    else
      AssertThrow(false, ExcMessage("no single-term model for '" + name + "'"));
    return result;
  }

  inline std::string
  joined(const std::vector<std::string> &names)
  {
    std::string text;
    for (const std::string &name : names)
      text += (text.empty() ? "" : ", ") + name;
    return text;
  }

  inline bool
  check_relative_equal(ConditionalOStream &out,
                       const std::string  &what,
                       const double        value,
                       const double        expected,
                       const double        tolerance)
  {
    const double scale = std::max(std::abs(value), std::abs(expected));
    return check_below(out,
                       what,
                       scale > 0. ? std::abs(value - expected) / scale : 0.,
                       tolerance);
  }

} // namespace clothsim::test
