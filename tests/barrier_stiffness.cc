// IPC's adaptive barrier stiffness (physics/barrier_stiffness.h, 'Contact/Adaptive
// barrier stiffness').
// 1. The rule: the scale doubles only at an iterate whose closest pair is below the
//    stiffening distance and below the previous iterate's (or the step start's), up to
//    its largest value; never without 'adaptive'; an attempt starts from the scale last
//    committed (a failed attempt's raise is taken back); a checkpoint keeps the committed
//    scale, and a bad one is refused.
// 2. Its use: the sheet of params/contact/sheet-on-sphere.prm (N = 21) 2 mm above a
//    sphere, with edge contact (the vertices' barrier and the core pairs), and folded
//    onto itself at a crease (self-contact, 'creases'): with the scale restored to 4 (as
//    from a checkpoint) each term's energy and gradient are 4 times the unscaled ones (to
//    1e-12), and so are the obstacle's force and the lagged friction's μ λ. At the
//    folded state (a hinge 0.6 d̂ apart, below a stiffening distance of d̂), an iterate
//    that closes the hinge further raises the self-contact's scale, one that opens it
//    does not, and the same on every rank; a retry (no commit_step) starts from the
//    scale before, the next step after commit_step from the raised one.

#include "physics/barrier_stiffness.h"
#include "app/mpi_session.h"
#include "contact_checks.h"
#include "io/collective.h"
#include "physics/self_contact.h"
#include "scene/obstacles.h"
#include "solvers/blas_kernels.h"

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  const std::string sphere_scene = "params/contact/sheet-on-sphere.prm";
  const std::string mesh_21      = "Mesh/Mesh file=../../meshes/swing-21.msh";

  bool
  check_rule(ConditionalOStream &pcout)
  {
    physics::AdaptiveStiffness stiffness({true, 1e-3, 8.});
    stiffness.begin_attempt(std::numeric_limits<double>::infinity());
    bool passed = true;
    // (distance, raised?, scale after)
    const std::vector<std::tuple<double, bool, double>> steps = {{2e-3, false, 1.},
                                                                 {5e-4, true, 2.},
                                                                 {4e-4, true, 4.},
                                                                 {4e-4, false, 4.},
                                                                 {6e-4, false, 4.},
                                                                 {3e-4, true, 8.},
                                                                 {1e-4, false, 8.}};
    unsigned int                                        wrong = 0;
    for (const auto &[distance, raised, scale] : steps)
      wrong += stiffness.observe(distance) != raised || stiffness.scale() != scale;
    passed &= check_equal(pcout, "rule: iterates judged wrongly", wrong, 0u);
    passed &= check_equal(pcout, "rule: times raised", stiffness.raised(), 3u);
    stiffness.commit();
    physics::AdaptiveStiffness again({true, 1e-3, 16.});
    again.restore(stiffness.saved());
    again.begin_attempt(2e-4);
    passed &= check(pcout,
                    !again.observe(2e-4) && again.observe(1e-4) && again.scale() == 16.,
                    "rule: restored at 8, not raised at the start's distance, raised "
                    "below it");
    bool refused = false;
    try
      {
        again.restore({0.5});
      }
    catch (const std::exception &)
      {
        refused = true;
      }
    passed &= check(pcout, refused, "rule: a scale below 1 is refused");
    // A failed attempt's raise is taken back by the next attempt; a committed one is not.
    physics::AdaptiveStiffness retried({true, 1e-3, 8.});
    retried.begin_attempt(5e-4);
    retried.observe(4e-4);
    const std::vector<double> during = retried.saved();
    retried.begin_attempt(5e-4);
    const double after_retry = retried.scale();
    retried.observe(4e-4);
    retried.commit();
    retried.begin_attempt(5e-4);
    passed &= check(pcout,
                    during == std::vector<double>{1.} && after_retry == 1. &&
                      retried.scale() == 2. && retried.saved() == std::vector<double>{2.},
                    "rule: a retry starts from the committed scale (1), a checkpoint "
                    "during an attempt keeps it; once committed (2) it stays");
    physics::AdaptiveStiffness fixed({false, 1e-3, 8.});
    fixed.begin_attempt(1.);
    passed &= check(pcout,
                    !fixed.observe(1e-6) && fixed.scale() == 1. && fixed.saved().empty(),
                    "rule: not adaptive, never raised nor saved");
    return passed;
  }

  // Energy (summed over ranks) and gradient of a term at u (ghosted).
  std::pair<double, VectorType>
  value_and_gradient(const physics::GlobalTerm &term,
                     const ClothModel          &model,
                     const VectorType          &u,
                     const StepTerms           &step)
  {
    VectorType gradient;
    model.initialize_owned(gradient);
    const double value =
      term.add_to_step(u, step, AffineConstraints<double>(), &gradient, nullptr, nullptr);
    gradient.compress(VectorOperation::add);
    return {Utilities::MPI::sum(value, MPI_COMM_WORLD), gradient};
  }

  // |b - 4 a| / |4 a| for energies and gradients.
  double
  four_times(const std::pair<double, VectorType> &a,
             const std::pair<double, VectorType> &b)
  {
    VectorType difference(b.second);
    difference.add(-4., a.second);
    return std::max(std::abs(b.first - 4. * a.first) / std::abs(4. * a.first),
                    difference.l2_norm() / (4. * a.second.l2_norm()));
  }

  double
  total_mu_lambda(const physics::LaggedContacts &contacts)
  {
    double sum = 0.;
    for (const physics::LaggedContact &contact : contacts.lagged_contacts())
      sum += contact.counted ? contact.mu_lambda : 0.;
    return Utilities::MPI::sum(sum, MPI_COMM_WORLD);
  }

  bool
  check_obstacle_scaling(ConditionalOStream &pcout)
  {
    const std::vector<std::string> sphere_below = {
      mesh_21,
      "Obstacle 1/Center=0.5, 0.5, -1.002",
      "Obstacle 1/Radius=1",
      "Contact/Adaptive barrier stiffness=true"};
    const auto scene =
      load_scene(source_path(sphere_scene), sphere_below, MPI_COMM_WORLD);
    const ClothModel        &model = *scene->model;
    const ContactParameters &given = scene->parameters().contact;
    VectorType               masses;
    model.lumped_masses(masses);
    physics::ObstacleContact contact(make_obstacles(given, source_path(sphere_scene)),
                                     contact_settings(given),
                                     model.get_discretization(),
                                     masses);
    const double             dt = 1. / 60.;
    VectorType               u_n, u_new, at;
    model.initialize_owned(u_n);
    model.initialize_owned(u_new);
    model.initialize_ghosted(at);
    contact.begin_step(0., dt, u_n, u_new, model.get_constraints());
    StepTerms step;
    step.time              = dt;
    at                     = u_n;
    const auto   unscaled  = value_and_gradient(contact, model, at, step);
    const double force     = contact.report(at, dt).forces[0][2];
    const double mu_lambda = total_mu_lambda(contact);
    contact.restore_state({4.});
    contact.begin_step(0., dt, u_n, u_new, model.get_constraints());
    bool passed = check_above(pcout, "sphere: energy at rest, J", unscaled.first, 0.);
    passed &=
      check_below(pcout,
                  "sphere, scale 4: energy and gradient / 4 times unscaled - 1",
                  four_times(unscaled, value_and_gradient(contact, model, at, step)),
                  1e-12);
    passed &= check_near(pcout,
                         "sphere, scale 4: force / 4 times unscaled",
                         contact.report(at, dt).forces[0][2] / (4. * force),
                         1.,
                         1e-12);
    passed &= check_near(pcout,
                         "sphere, scale 4: friction's μ λ / 4 times unscaled",
                         total_mu_lambda(contact) / (4. * mu_lambda),
                         1.,
                         1e-12);
    return passed;
  }

  bool
  check_self_contact(ConditionalOStream &pcout)
  {
    const auto               scene = load_scene(source_path(sphere_scene),
                                  {mesh_21,
                                                 "Contact/Adaptive barrier stiffness=true",
                                                 "Contact/Stiffening distance=1",
                                                 "Contact/Self friction=0.3"},
                                  MPI_COMM_WORLD);
    const ClothModel        &model = *scene->model;
    const ContactParameters &given = scene->parameters().contact;
    const double             d_hat = given.thickness, h = 0.05;
    VectorType               masses;
    model.lumped_masses(masses);
    physics::SelfContact crease(
      contact_settings(given), model.get_discretization(), masses, false, 0.3, true);
    // The upper half (y > 0.5) turned about y = 0.5 until its first row is `gap` above
    // the lower half.
    const auto folded = [&](const double gap, VectorType &u) {
      const double theta = M_PI - std::asin(gap / h);
      for (const auto &element : model.get_discretization().elements())
        for (unsigned int v = 0; v < 3; ++v)
          {
            const Point<3> &X = element.reference[v];
            const double    r = X[1] - 0.5;
            if (r <= 1e-9 || !model.owned_dofs().is_element(element.dofs[3 * v]))
              continue;
            u[element.dofs[3 * v + 1]] = 0.5 + r * std::cos(theta) - X[1];
            u[element.dofs[3 * v + 2]] = r * std::sin(theta);
          }
      u.compress(VectorOperation::insert);
    };
    VectorType u, at;
    model.initialize_owned(u);
    model.initialize_ghosted(at);
    folded(0.6 * d_hat, u);
    at = u;
    StepTerms step;
    crease.lag_friction(at, 1. / 60.);
    const auto   unscaled  = value_and_gradient(crease, model, at, step);
    const double mu_lambda = total_mu_lambda(crease);
    crease.restore_state({4.});
    crease.lag_friction(at, 1. / 60.);
    bool passed = check_above(pcout, "crease: energy, J", unscaled.first, 0.);
    passed &=
      check_below(pcout,
                  "crease, scale 4: energy and gradient / 4 times unscaled - 1",
                  four_times(unscaled, value_and_gradient(crease, model, at, step)),
                  1e-12);
    passed &= check_near(pcout,
                         "crease, scale 4: friction's μ λ / 4 times unscaled",
                         total_mu_lambda(crease) / (4. * mu_lambda),
                         1.,
                         1e-12);
    // From the fold at 0.6 d̂: opened to 0.8 d̂ no raise, closed to 0.4 d̂ a raise (each
    // judged after the barrier is assembled there, as in Newton's line search).
    crease.begin_attempt(at, 0.);
    folded(0.8 * d_hat, u);
    at = u;
    value_and_gradient(crease, model, at, step);
    const bool open = crease.adapt_stiffness();
    folded(0.4 * d_hat, u);
    at = u;
    value_and_gradient(crease, model, at, step);
    const bool close = crease.adapt_stiffness();
    passed &=
      check(pcout,
            !open && close && crease.barrier_stiffness().scale() == 8. &&
              io::on_all_ranks(crease.barrier_stiffness().scale() == 8., MPI_COMM_WORLD),
            "crease: opened, not raised; closed, raised from 4 to 8");
    // A retry of the step (no commit) starts again from 4; raised there to 8 and the
    // step committed, the next step starts from 8, and a checkpoint keeps 8.
    crease.begin_attempt(at, 0.);
    const double retry = crease.barrier_stiffness().scale();
    folded(0.3 * d_hat, u);
    at = u;
    value_and_gradient(crease, model, at, step);
    const bool raised_again = crease.adapt_stiffness();
    crease.commit_step(at, u);
    crease.begin_attempt(at, 0.);
    passed &=
      check(pcout,
            retry == 4. && raised_again && crease.barrier_stiffness().scale() == 8. &&
              crease.saved_state() == std::vector<double>{8.},
            "crease: a retry starts from the committed 4; committed at 8, the "
            "next step starts from 8");
    return passed;
  }
} // namespace

int
main(int argc, char **argv)
{
  clothsim::MpiSession mpi(argc, argv);
  clothsim::select_blas_kernels(); // as the clothsim executable does
  ConditionalOStream pcout(std::cout,
                           Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0);
  bool               passed = check_rule(pcout);
  passed &= check_obstacle_scaling(pcout);
  passed &= check_self_contact(pcout);
  pcout << (passed ? "PASSED" : "FAILED") << std::endl;
  return passed ? 0 : 1;
}
