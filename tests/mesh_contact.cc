// Contact with triangle-mesh obstacles: the broad phase and the term (the pair kernels
// are tests/contact_pairs.cc):
// 1. The bounding-volume hierarchy finds exactly the overlapping boxes of 5,000; both
//    hierarchies descended at once give the pairs within a margin of these and 1,000
//    more boxes, and of these alone, each once, as testing every pair does.
// 2. The contact and friction terms of a sheet 2 mm above the apex of a pyramid mesh
//    (its apex vertex against cloth triangles, its edges against cloth edges, cloth
//    vertices against its faces): the step potential's gradient and Hessian against
//    differences (relative 1e-5), friction static and kinetic.
// 3. The list of near pairs that evaluations reuse (MeshContact::for_each_near_pair)
//    against a full search: along a path that moves the sheet's vertices near the apex
//    by up to 0.9 mm per state (25 states, pairs coming within d̂ = 5 mm and leaving; the
//    list kept while no vertex has moved by d̂ and made again after), the barrier and
//    its gradient of one contact term equal those of a new term at every state, to the
//    last bit.

#include "contact_checks.h"
#include "physics/aabb_tree.h"

#include <random>

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  bool
  check_tree(ConditionalOStream &pcout)
  {
    std::mt19937                           random(17);
    std::uniform_real_distribution<double> u(0., 1.);
    std::vector<physics::Box>              boxes;
    for (unsigned int k = 0; k < 5000; ++k)
      {
        const Point<3> a(u(random), u(random), u(random));
        const Point<3> b = a + 0.03 * Point<3>(u(random), u(random), u(random));
        boxes.push_back(physics::Box::around(std::array<Point<3>, 2>{{a, b}}));
      }
    const physics::AabbTree tree(boxes);
    unsigned int            wrong = 0, found_total = 0;
    for (unsigned int q = 0; q < 200; ++q)
      {
        const Point<3>     a(u(random), u(random), u(random));
        const physics::Box query =
          physics::Box::around(std::array<Point<3>, 1>{{a}}, 0.1 * u(random));
        std::vector<unsigned int> found;
        tree.find(query, found);
        std::sort(found.begin(), found.end());
        std::vector<unsigned int> brute;
        for (unsigned int k = 0; k < boxes.size(); ++k)
          if (boxes[k].overlaps(query))
            brute.push_back(k);
        wrong += found == brute ? 0 : 1;
        found_total += found.size();
      }
    pcout << "  " << found_total << " overlaps found in 200 queries" << std::endl;
    bool passed = check_equal(pcout, "queries with a wrong answer", wrong, 0u);

    // Both hierarchies descended at once: the pairs of these boxes and 1,000 others
    // within a margin, and the pairs i < j of these boxes alone, each once, as all
    // pairs tested one by one.
    std::vector<physics::Box> others;
    for (unsigned int k = 0; k < 1000; ++k)
      {
        const Point<3> a(u(random), u(random), u(random));
        others.push_back(physics::Box::around(std::array<Point<3>, 1>{{a}}));
      }
    const physics::AabbTree other_tree(others);
    const double            margin = 0.01;
    using Pairs                    = std::vector<std::pair<unsigned int, unsigned int>>;
    Pairs between, within, between_brute, within_brute;
    tree.for_each_overlap(other_tree, margin, [&](unsigned int i, unsigned int j) {
      between.emplace_back(i, j);
    });
    tree.for_each_overlap(margin, [&](unsigned int i, unsigned int j) {
      within.emplace_back(i, j);
    });
    for (unsigned int i = 0; i < boxes.size(); ++i)
      {
        for (unsigned int j = 0; j < others.size(); ++j)
          if (boxes[i].within(others[j], margin))
            between_brute.emplace_back(i, j);
        for (unsigned int j = i + 1; j < boxes.size(); ++j)
          if (boxes[i].within(boxes[j], margin))
            within_brute.emplace_back(i, j);
      }
    std::sort(between.begin(), between.end());
    std::sort(within.begin(), within.end());
    pcout << "  " << between_brute.size() << " and " << within_brute.size()
          << " pairs within the margin" << std::endl;
    passed &= check_above(pcout, "pairs between the two sets", between_brute.size(), 100);
    passed &= check_equal(pcout,
                          "pairs between the two sets, all found once",
                          between == between_brute,
                          true);
    passed &= check_equal(pcout,
                          "pairs within one set, all found once",
                          within == within_brute,
                          true);
    return passed;
  }

  // A flat pyramid, 2 cm high on a 0.4 m square, its apex at `apex`.
  std::shared_ptr<const physics::ObstacleSurface>
  pyramid(const Point<3> &apex)
  {
    std::vector<Point<3>> v = {apex,
                               apex + Point<3>(-0.2, -0.2, -0.02),
                               apex + Point<3>(0.2, -0.2, -0.02),
                               apex + Point<3>(0.2, 0.2, -0.02),
                               apex + Point<3>(-0.2, 0.2, -0.02)};
    return std::make_shared<const physics::ObstacleSurface>(
      v,
      std::vector<std::array<unsigned int, 3>>{
        {{0, 1, 2}}, {{0, 2, 3}}, {{0, 3, 4}}, {{0, 4, 1}}},
      std::vector<std::array<unsigned int, 2>>{
        {{0, 1}}, {{0, 2}}, {{0, 3}}, {{0, 4}}, {{1, 2}}, {{2, 3}}, {{3, 4}}, {{4, 1}}});
  }

  // The pyramid as a static obstacle with μ = 0.4 for the unit square sheet at z = 0:
  // its apex 2 mm below a point inside a triangle, off the mesh's lines.
  std::vector<physics::Obstacle>
  pyramid_obstacle()
  {
    physics::ObstacleShape shape;
    shape.core    = physics::ObstacleCore::mesh;
    shape.surface = pyramid(Point<3>(0.513, 0.487, -0.002));
    std::vector<physics::Obstacle> obstacles;
    obstacles.emplace_back(
      "pyramid",
      shape,
      0.4,
      [](double) { return Tensor<1, 3>(); },
      Tensor<1, 3>({0., 0., 1.}),
      [](double) { return 0.; });
    return obstacles;
  }

  bool
  check_terms(ConditionalOStream &pcout, const std::string &mesh)
  {
    return check_contact_terms(pcout, mesh, pyramid_obstacle(), 3);
  }

  bool
  check_near_list(ConditionalOStream &pcout, const std::string &mesh)
  {
    const std::vector<physics::Obstacle> obstacles = pyramid_obstacle();
    const auto scene = load_scene(source_path("params/contact/sheet-on-sphere.prm"),
                                  {"Mesh/Mesh file=" + mesh},
                                  MPI_COMM_WORLD);
    const ClothModel &model = *scene->model;
    VectorType        masses;
    model.lumped_masses(masses);
    const ContactParameters       &given = scene->parameters().contact;
    const physics::ContactSettings settings{given.thickness,
                                            given.barrier_acceleration,
                                            given.slip_velocity};
    const auto                     contact_model = [&]() {
      auto terms = std::make_unique<physics::Model>(model.get_discretization(),
                                                    model.get_constraints());
      terms->add(std::make_unique<physics::ObstacleContact>(
        obstacles, settings, model.get_discretization(), masses));
      return terms;
    };
    const std::unique_ptr<physics::Model> kept = contact_model();

    VectorType path, u, ghosted, g_kept, g_new;
    for (VectorType *vector : {&path, &u, &g_kept, &g_new})
      model.initialize_owned(*vector);
    model.initialize_ghosted(ghosted);
    fill(model, path, 1e-3, 0., 7);
    StepTerms    step;
    unsigned int differing = 0, in_contact = 0;
    double       largest = 0.;
    for (unsigned int k = 0; k < 25; ++k)
      {
        u = path;
        u *= 0.5 * k; // up to 12 mm per coordinate
        ghosted             = u;
        g_kept              = 0.;
        g_new               = 0.;
        const double e_kept = kept->assemble(ghosted, step, &g_kept, nullptr);
        const double e_new  = contact_model()->assemble(ghosted, step, &g_new, nullptr);
        g_kept -= g_new;
        differing += e_kept != e_new || g_kept.linfty_norm() != 0.;
        in_contact += e_new > 0.;
        largest = std::max(largest, e_new);
      }
    pcout << "  near pairs' list: " << in_contact << " of 25 states in contact, largest "
          << "barrier " << largest << " J" << std::endl;
    return check_at_least(pcout, "states in contact", in_contact, 20u) &
           check_equal(pcout, "states whose barrier or gradient differ", differing, 0u);
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &pcout  = env.pcout;
  bool                passed = true;
  pcout << "Bounding-volume hierarchy" << std::endl;
  passed &= check_tree(pcout);
  pcout << "Terms: a sheet over a pyramid" << std::endl;
  const std::filesystem::path root = scratch_directory("clothsim-mesh-contact");
  const std::string           mesh =
    scratch_mesh(root / "mesh", {"swing-21.geo", "swing-grid.geo.inc"});
  passed &= check_terms(pcout, mesh);
  pcout << "Near pairs' list against a full search" << std::endl;
  passed &= check_near_list(pcout, mesh);
  return finish(pcout, passed);
}
