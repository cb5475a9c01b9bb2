// Uniaxial stretch of a flat strip (tests/scenes/uniaxial_stretch.prm), solved statically
// with the project's Newton solver on an unstructured mesh. Linear triangles represent
// the uniform state exactly, so the discrete solution must match the St. Venant–Kirchhoff
// closed form:
//   stretch λ = 1.1, E_xx = (λ² - 1)/2, plane stress with S_yy = 0 gives E_yy = -ν E_xx
//   and S_xx = k E_xx; the pulling force on the right edge is F = W λ S_xx (first
//   Piola-Kirchhoff times the reference width W), and the width shrinks to W sqrt(1 + 2
//   E_yy).
// Asserts the force and the contraction within 1e-8 relative, and a uniform strain field.
// The displacement is affine, u = ((λ - 1) X, (sqrt(1 + 2 E_yy) - 1) Y, 0), which linear
// interpolation represents exactly: probes between vertices (Output/Probes 'inside', and
// 'lifted', given 2 µm above the strip) must read it to 1e-8 relative, at their surface
// points.

#include "test_support.h"

#include <algorithm>
#include <cmath>

using namespace clothsim;
using namespace clothsim::test;

int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &pcout = env.pcout;

  const SceneRun    run     = run_scene(source_path("tests/scenes/uniaxial_stretch.prm"),
                                 {},
                                 scratch_directory("clothsim-uniaxial"),
                                 env.communicator);
  const ClothModel &model   = run.model();
  const RunSummary &summary = run.summary;
  const VectorType &u       = run.displacement;

  const double length = 2., width = 0.5, k = 100., nu = 0.3, stretch = 1.1;
  const double E_xx = 0.5 * (stretch * stretch - 1.), E_yy = -nu * E_xx;
  const double expected_force       = width * stretch * k * E_xx;
  const double expected_contraction = width * (std::sqrt(1. + 2. * E_yy) - 1.);

  // Reaction: the internal forces' x components summed over the right edge.
  const double force = edge_reaction_x(model, u, length);

  // Contraction of the far corner (2, 0.5): uy.
  const double contraction = run.probe_displacement(run.scene->probes.at(0).name)[1];

  // Uniform strain: every triangle's Green strain norm equals sqrt(E_xx² + E_yy²).
  const std::vector<double> strain          = model.cell_field(u, "green_strain");
  const double              expected_strain = std::sqrt(E_xx * E_xx + E_yy * E_yy);
  double                    worst_strain    = 0.;
  for (const double value : strain)
    worst_strain =
      std::max(worst_strain, std::abs(value - expected_strain) / expected_strain);
  worst_strain = Utilities::MPI::max(worst_strain, env.communicator);

  const double force_error = std::abs(force - expected_force) / expected_force;
  const double contraction_error =
    std::abs(contraction - expected_contraction) / std::abs(expected_contraction);
  pcout << "load steps " << summary.steps << ", Newton iterations "
        << summary.newton_iterations << "\nforce " << force << " N (closed form "
        << expected_force << ", relative error " << force_error << ")\ncontraction "
        << contraction << " m (closed form " << expected_contraction
        << ", relative error " << contraction_error
        << ")\nworst relative deviation of a triangle's strain norm from the closed form "
        << worst_strain << std::endl;

  bool passed = force_error < 1e-8 && contraction_error < 1e-8 && worst_strain < 1e-8;

  // Probes between vertices: interpolated in their triangles.
  const double shrink = std::sqrt(1. + 2. * E_yy) - 1.;
  for (const ProbeLocation &probe : run.scene->probes)
    {
      const Point<3>    &X = probe.reference_point;
      const Tensor<1, 3> expected({(stretch - 1.) * X[0], shrink * X[1], 0.});
      const double       error =
        (run.probe_displacement(probe.name) - expected).norm() / expected.norm();
      passed &=
        check_below(pcout, "probe " + probe.name + ": relative error", error, 1e-8);
    }
  const ProbeLocation &inside = run.scene->probes.at(1),
                      &lifted = run.scene->probes.at(2);
  // Not snapped: the point itself, inside a triangle (no weight near 0 or 1).
  passed &= check_below(pcout,
                        "inside: distance from its point [m]",
                        inside.reference_point.distance(Point<3>(1.2345, 0.3141, 0.)),
                        1e-14);
  passed &= check_below(pcout,
                        "inside: largest barycentric weight",
                        *std::max_element(inside.weights.begin(), inside.weights.end()),
                        0.999);
  passed &= check_above(pcout,
                        "inside: smallest barycentric weight",
                        *std::min_element(inside.weights.begin(), inside.weights.end()),
                        1e-3);
  // Lifted: located at its foot on the strip, 2 µm away.
  passed &= check_below(pcout,
                        "lifted: |distance - 2e-6| [m]",
                        std::abs(lifted.distance - 2e-6),
                        1e-15);
  passed &=
    check_below(pcout,
                "lifted: distance of its surface point from (0.777, 0.222, 0) [m]",
                lifted.reference_point.distance(Point<3>(0.777, 0.222, 0.)),
                1e-14);
  return finish(pcout, passed);
}
