// Self-contact restricted to creases (physics/self_contact.h, `Contact/Self contact =
// creases`: the pairs of each interior edge's two triangles only).
// 1. On 2,000 random hinges, turned and moved rigidly, the bound that decides which
//    hinges are visited is 0 where a hinge is folded by more than 90 degrees, else
//    positive and at most its closest pair's distance (0.69 of it on average).
// 2. The sheet of params/contact/sheet-on-sphere.prm on the N = 21 swing mesh (5 cm
//    triangles, d̂ = 5 mm), its upper half turned about y = 0.5 (a line of mesh edges):
//    no energy folded by 60 degrees; closed until its first row is 0.6 d̂ above the lower
//    half, a positive energy below full self-contact's, and the gradient and exact
//    Hessian against differences (1e-5); from 60 degrees straight on through the lower
//    half, the step is capped and no hinge's pair comes within a tenth of its distance
//    at the start (without the hinges' motion in the filter the cap is 1 and a pair
//    comes to 0.003 of it).

#include "app/mpi_session.h"
#include "contact_checks.h"
#include "physics/self_contact.h"
#include "solvers/blas_kernels.h"

#include <deal.II/physics/transformations.h>

#include <random>

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  const std::string sphere_scene = "params/contact/sheet-on-sphere.prm";
  const std::string mesh_21      = "Mesh/Mesh file=../../meshes/swing-21.msh";

  // `Self contact = creases`: the hinges' bound on random hinges, then the sheet's upper
  // half folded about y = 0.5 (a line of mesh edges).
  bool
  check_creases(ConditionalOStream &pcout)
  {
    // Random hinges (edge length L, opposite vertices at s in [-L/2, 3L/2] along it and
    // heights in [L/10, L], opened by φ), turned and moved rigidly: the bound is 0 where
    // φ < 90 degrees, else positive and at most the closest of its four pairs.
    std::mt19937                           random(7);
    std::uniform_real_distribution<double> unit(0., 1.);
    unsigned int                           wrong_zero = 0, n_open = 0;
    double worst = std::numeric_limits<double>::infinity(), tightness = 0.;
    for (unsigned int k = 0; k < 2000; ++k)
      {
        const double       L = 0.5 + unit(random), phi = M_PI * unit(random);
        const Tensor<1, 3> axis({unit(random) - 0.5, unit(random) - 0.5, 1.});
        const auto rotation = Physics::Transformations::Rotations::rotation_matrix_3d(
          Point<3>(axis / axis.norm()), 2. * M_PI * unit(random));
        const auto place = [&](const double s, const double t, const double angle) {
          return Point<3>(rotation *
                            Tensor<1, 3>({s, t * std::cos(angle), t * std::sin(angle)}) +
                          Tensor<1, 3>({0.3, -0.2, 0.1}));
        };
        const Point<3> a = place(0., 0., 0.), b = place(L, 0., 0.),
                       p   = place(L * (2. * unit(random) - 0.5),
                                 L * (0.1 + 0.9 * unit(random)),
                                 0.),
                       q   = place(L * (2. * unit(random) - 0.5),
                                 L * (0.1 + 0.9 * unit(random)),
                                 phi);
        const double bound = physics::hinge_distance_bound(a, b, p, q);
        if (std::abs(phi - M_PI / 2.) < 1e-6)
          continue;
        if (phi < M_PI / 2.)
          {
            wrong_zero += bound != 0. ? 1 : 0;
            continue;
          }
        ++n_open;
        wrong_zero += bound > 0. ? 0 : 1;
        using K        = physics::PairKind;
        const double d = std::sqrt(
          std::min({physics::pair_squared_distance(K::point_triangle, {{p, a, b, q}}),
                    physics::pair_squared_distance(K::point_triangle, {{q, a, b, p}}),
                    physics::pair_squared_distance(K::edge_edge, {{p, a, b, q}}),
                    physics::pair_squared_distance(K::edge_edge, {{p, b, a, q}})}));
        worst = std::min(worst, d / bound);
        tightness += bound / d;
      }
    bool passed = check_equal(pcout,
                              "hinges: bound 0 where open, or not where folded",
                              wrong_zero,
                              0u);
    passed &=
      check_above(pcout,
                  "hinges open by 90 degrees or more: closest pair / bound, smallest",
                  worst,
                  1. - 1e-12);
    passed &=
      check_above(pcout, "hinges: bound / closest pair, mean", tightness / n_open, 0.3);

    const auto scene = load_scene(source_path(sphere_scene), {mesh_21}, MPI_COMM_WORLD);
    const ClothModel        &model = *scene->model;
    const ContactParameters &given = scene->parameters().contact;
    const double             d_hat = given.thickness, h = 0.05;
    VectorType               masses;
    model.lumped_masses(masses);
    const physics::ContactSettings settings{given.thickness,
                                            given.barrier_acceleration,
                                            given.slip_velocity};
    auto                       creases = std::make_unique<physics::SelfContact>(settings,
                                                          model.get_discretization(),
                                                          masses,
                                                          /*couple_pairs=*/true,
                                                          0.,
                                                          /*creases_only=*/true);
    physics::SelfContact      &crease  = *creases;
    const physics::SelfContact full(settings, model.get_discretization(), masses);
    physics::Model             terms(model.get_discretization(), model.get_constraints());
    terms.add(std::move(creases));
    // The upper half turned about the line y = 0.5 by θ (π: folded flat onto the lower),
    // shrunk across it by 0.8 and sheared along it by 0.3 (a vertex is then off the
    // lines where a pair's distance type changes).
    const auto folded = [&](const double theta, VectorType &u) {
      for (const auto &element : model.get_discretization().elements())
        for (unsigned int v = 0; v < 3; ++v)
          {
            const Point<3> &X = element.reference[v];
            const double    r = X[1] - 0.5;
            if (r <= 1e-9 || !model.owned_dofs().is_element(element.dofs[3 * v]))
              continue;
            u[element.dofs[3 * v]]     = 0.3 * r;
            u[element.dofs[3 * v + 1]] = 0.5 + 0.8 * r * std::cos(theta) - X[1];
            u[element.dofs[3 * v + 2]] = 0.8 * r * std::sin(theta);
          }
      u.compress(VectorOperation::insert);
    };
    VectorType u, v, at, d;
    model.initialize_owned(u);
    model.initialize_owned(d);
    model.initialize_ghosted(v);
    model.initialize_ghosted(at);
    const auto energy = [&](const physics::SelfContact &term) {
      return Utilities::MPI::sum(term.energy(at, v, nullptr), MPI_COMM_WORLD);
    };
    folded(M_PI / 3., u);
    at = u;
    passed &=
      check_equal(pcout, "creases: folded by 60 degrees, energy", energy(crease), 0.);
    // Folded until the first row of the upper half is 0.6 d̂ above the lower half.
    folded(M_PI - std::asin(0.6 * d_hat / (0.8 * h)), u);
    at                  = u;
    const double closed = energy(crease);
    passed &= check_above(pcout, "creases: closed to 0.6 d̂, energy, J", closed, 0.);
    passed &= check_below(pcout,
                          "creases: its energy / full self-contact's",
                          closed / energy(full),
                          1.);
    crease.update_couplings(at, at); // the pairs' couplings in the sparsity
    StepTerms step;
    step.projected_tangent = false;
    fill(model, d, 1., 0., 5);
    const Derivatives D = derivatives(terms, model, step, u, d, 1e-8);
    passed &=
      check_below(pcout, "creases: gradient against differences", D.gradient_error, 1e-5);
    passed &=
      check_below(pcout, "creases: Hessian against differences", D.hessian_error, 1e-5);

    // From 60 degrees straight toward 200 (the upper half through the lower): capped,
    // and no hinge's pair comes within a tenth of its distance at the start.
    VectorType start(u), through(u);
    folded(M_PI / 3., start);
    folded(M_PI * 10. / 9., through);
    through -= start;
    VectorType direction;
    model.initialize_ghosted(direction);
    direction = through;
    at        = start;
    const double alpha =
      Utilities::MPI::min(crease.step_cap(at, direction), MPI_COMM_WORLD);
    passed &=
      check_below(pcout, "creases: step cap through the lower half", alpha, 0.999);
    const double at_start = crease.report(at, 1.).min_distance;
    double       closest  = at_start;
    for (unsigned int k = 1; k <= 200; ++k)
      {
        VectorType w(start);
        w.add(alpha * k / 200., through);
        at      = w;
        closest = std::min(closest, crease.report(at, 1.).min_distance);
      }
    passed &=
      check_above(pcout,
                  "creases: smallest hinge distance on the capped path / at its start",
                  closest / at_start,
                  0.1);
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
  const bool         passed = check_creases(pcout);
  pcout << (passed ? "PASSED" : "FAILED") << std::endl;
  return passed ? 0 : 1;
}
