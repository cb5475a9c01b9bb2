// The orthotropic sheet (physics/sheet_stiffness.h) against closed forms:
// 1. Its constitutive tensor with isotropic constants, built through the material frame,
//    equals the isotropic one on random triangles in space with random warps.
// 2. Uniaxial stress along θ = 0 (warp), 90° (weft), 45° (bias) and random angles: the
//    Green strain of the engineering compliance (ε_11 = σ_11/k_1 - ν_12 σ_22/k_1,
//    ε_22 = -ν_12 σ_11/k_1 + σ_22/k_2, 2 ε_12 = σ_12/g) applied exactly to a triangle
//    (F = sqrt(I + 2E) in the plane) gives back, from the element's gradient, the stress
//    σ t⊗t and nothing else, so the uniaxial stiffness is
//      1/k(θ) = cos⁴θ/k_1 + (1/g - 2 ν_12/k_1) sin²θ cos²θ + sin⁴θ/k_2.
// 3. The uniaxial strip (tests/scenes/uniaxial_stretch.prm, 10 % stretch, static) with
// the
//    warp along and across the strip: the pull and the contraction of St.
//    Venant–Kirchhoff with k_1 and ν_12 (warp) or k_2 and ν_21 = ν_12 k_2/k_1 (weft),
//    within 1e-8.
// 4. Bending lengths: the heavy cantilever (params/benchmarks/heavy-cantilever.prm, D_1 =
// 1
//    N·m, D_2 = 0.4 N·m, ν = 0, level 1) along the warp (α = qL³/(D_1 b) = 8: tip
//    deflection 0.64063 L) and along the weft (α = 20: 0.82988 L), exact elastica of
//    ../shared/references/benchmarks.md, within 0.3 %.

#include "physics/membrane.h"
#include "physics/sheet_stiffness.h"
#include "test_support.h"

#include <cmath>
#include <random>

using namespace clothsim;
using namespace clothsim::physics;
using namespace clothsim::test;

namespace
{
  double
  relative_difference(const Tensor<4, 2> &a, const Tensor<4, 2> &b)
  {
    return (a - b).norm() / b.norm();
  }

  // The orthonormal material frame of a reference triangle: the warp projected onto its
  // plane, the normal times it, and the normal.
  std::array<Tensor<1, 3>, 3>
  material_frame(const TrianglePositions &X, const Tensor<1, 3> &warp)
  {
    Tensor<1, 3> n = cross_product_3d(X[1] - X[0], X[2] - X[0]);
    n /= n.norm();
    Tensor<1, 3> e1 = warp - (warp * n) * n;
    e1 /= e1.norm();
    return {{e1, cross_product_3d(n, e1), n}};
  }
} // namespace

int
main(int argc, char **argv)
{
  Environment                            env(argc, argv);
  ConditionalOStream                    &pcout = env.pcout;
  std::mt19937                           generator(7);
  std::uniform_real_distribution<double> uniform(-1., 1.);

  const auto random_triangle = [&]() {
    TrianglePositions X;
    for (auto &p : X)
      for (unsigned int d = 0; d < 3; ++d)
        p[d] = 0.1 * uniform(generator);
    return X;
  };
  const auto random_direction = [&]() {
    Tensor<1, 3> w;
    for (unsigned int d = 0; d < 3; ++d)
      w[d] = uniform(generator);
    return w;
  };

  // 1. Isotropic constants through the frame.
  {
    double worst = 0.;
    for (unsigned int trial = 0; trial < 100; ++trial)
      {
        const TrianglePositions X    = random_triangle();
        const MembraneRestData  rest = membrane_rest_data(X);
        if (rest.area < 1e-4)
          continue;
        const double k          = 100. + 50. * uniform(generator),
                     nu         = 0.2 + 0.2 * uniform(generator);
        SheetStiffness frame    = membrane_sheet_stiffness(k, nu, 0., 0.);
        frame.isotropic         = false;
        const Tensor<1, 3> warp = random_direction();
        worst                   = std::max(
          worst,
          relative_difference(covariant_stiffness(frame, X, rest.inverse_metric, warp),
                              covariant_stiffness(membrane_sheet_stiffness(k, nu, 0., 0.),
                                                  X,
                                                  rest.inverse_metric,
                                                  warp)));
        SheetStiffness plate = bending_sheet_stiffness(1e-5 * k, nu, -1.);
        worst =
          std::max(worst,
                   relative_difference(
                     covariant_stiffness(bending_sheet_stiffness(1e-5 * k, nu, 1e-5 * k),
                                         X,
                                         rest.inverse_metric,
                                         warp),
                     covariant_stiffness(plate, X, rest.inverse_metric, warp)));
      }
    check_below(pcout,
                "isotropic constants through the material frame: relative difference "
                "of C^abcd",
                worst,
                1e-13);
  }

  // 2. Uniaxial stress at angles from the warp.
  {
    const double        k1 = 300., k2 = 120., g = 15., nu12 = 0.3, sigma = 5.; // N/m
    MembraneMaterial    material{k1, nu12, k2, g};
    double              worst_stress = 0., worst_modulus = 0.;
    const double        pi     = numbers::PI;
    std::vector<double> angles = {0., pi / 2., pi / 4.};
    for (unsigned int i = 0; i < 20; ++i)
      angles.push_back(pi * uniform(generator));
    for (const double theta : angles)
      {
        TrianglePositions X = random_triangle();
        while (membrane_rest_data(X).area < 1e-3)
          X = random_triangle();
        const MembraneRestData rest = membrane_rest_data(X);
        material.warp_direction     = random_direction();
        const auto   e              = material_frame(X, material.warp_direction);
        const double c = std::cos(theta), s = std::sin(theta);
        // Engineering compliance in the frame.
        const double s11 = sigma * c * c, s22 = sigma * s * s, s12 = sigma * s * c;
        Tensor<2, 2> E;
        E[0][0] = s11 / k1 - nu12 * s22 / k1;
        E[1][1] = -nu12 * s11 / k1 + s22 / k2;
        E[0][1] = E[1][0] = 0.5 * s12 / g;
        // U = sqrt(I + 2E) of a symmetric positive 2x2 matrix: (C + sqrt(det C) I) /
        // sqrt(tr C + 2 sqrt(det C)).
        Tensor<2, 2> C = 2. * E;
        C[0][0] += 1.;
        C[1][1] += 1.;
        const double root_det = std::sqrt(determinant(C));
        Tensor<2, 2> U        = C;
        U[0][0] += root_det;
        U[1][1] += root_det;
        U /= std::sqrt(trace(C) + 2. * root_det);
        // x_v = X_0 + F (X_v - X_0), F = U on the plane (e_1, e_2).
        TrianglePositions x = X;
        for (unsigned int v = 1; v < 3; ++v)
          {
            const Tensor<1, 3> d    = X[v] - X[0];
            const double       p[2] = {d * e[0], d * e[1]};
            x[v]                    = X[0] + (U[0][0] * p[0] + U[0][1] * p[1]) * e[0] +
                   (U[1][0] * p[0] + U[1][1] * p[1]) * e[1];
          }
        ElementVector gradient;
        membrane_energy_gradient_hessian(
          membrane_stiffness(material, X, rest), rest, x, 0., gradient, nullptr);
        // f_a = |T̄| S^ab a_b: S^ab = (f_a · a_c) (a⁻¹)^cb / |T̄|, then the frame's
        // S_ij = S^ab (Ā_a · e_i)(Ā_b · e_j).
        const Tensor<1, 3> a[2]     = {x[1] - x[0], x[2] - x[0]};
        const Tensor<1, 3> A_ref[2] = {X[1] - X[0], X[2] - X[0]};
        Tensor<2, 2>       metric, fa;
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            {
              metric[i][j] = a[i] * a[j];
              Tensor<1, 3> f;
              for (unsigned int d = 0; d < 3; ++d)
                f[d] = gradient[3 * (i + 1) + d];
              fa[i][j] = f * a[j] / rest.area;
            }
        const Tensor<2, 2> S_covariant = fa * invert(metric);
        Tensor<2, 2>       S_frame;
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            for (unsigned int p = 0; p < 2; ++p)
              for (unsigned int q = 0; q < 2; ++q)
                S_frame[i][j] +=
                  S_covariant[p][q] * (A_ref[p] * e[i]) * (A_ref[q] * e[j]);
        Tensor<2, 2> expected;
        expected[0][0] = s11;
        expected[1][1] = s22;
        expected[0][1] = expected[1][0] = s12;
        worst_stress = std::max(worst_stress, (S_frame - expected).norm() / sigma);
        // The uniaxial stiffness σ / E_tt against the closed form.
        const double strain_along =
          c * c * E[0][0] + 2. * s * c * E[0][1] + s * s * E[1][1];
        const double closed_form =
          1. / (std::pow(c, 4) / k1 + (1. / g - 2. * nu12 / k1) * s * s * c * c +
                std::pow(s, 4) / k2);
        const double modulus =
          S_frame[0][0] * c * c + 2. * S_frame[0][1] * s * c + S_frame[1][1] * s * s;
        worst_modulus =
          std::max(worst_modulus,
                   std::abs(modulus / strain_along - closed_form) / closed_form);
        if (theta == 0. || theta == pi / 2. || theta == pi / 4.)
          pcout << "  uniaxial stiffness at " << theta * 180. / pi
                << " deg: " << modulus / strain_along << " N/m (closed form "
                << closed_form << ")\n";
      }
    check_below(pcout,
                "uniaxial stress at 23 angles: the element's stress differs from "
                "sigma t⊗t by (relative)",
                worst_stress,
                1e-10);
    check_below(pcout,
                "uniaxial stiffness against 1/k(θ) = c⁴/k1 + (1/g - 2ν/k1) s²c² + s⁴/k2 "
                "(relative)",
                worst_modulus,
                1e-10);
  }

  const std::string directory = scratch_directory("clothsim-orthotropic-sheet");

  // 3. The uniaxial strip along the warp and along the weft.
  for (const bool along_warp : {true, false})
    {
      const double      k1 = 100., k2 = 40., g = 10., nu12 = 0.3;
      const SceneRun    run = run_scene(source_path("tests/scenes/uniaxial_stretch.prm"),
                                     {"Material/Anisotropy=orthotropic",
                                         "Material/Stretch stiffness=" + number(k1),
                                         "Material/Weft stretch stiffness=" + number(k2),
                                         "Material/Shear stiffness=" + number(g),
                                         "Material/Poisson ratio=" + number(nu12),
                                         std::string("Material/Warp direction=") +
                                           (along_warp ? "1, 0, 0" : "0, 1, 0")},
                                     directory,
                                     env.communicator);
      const double      length = 2., width = 0.5, stretch = 1.1;
      const double      k    = along_warp ? k1 : k2;
      const double      nu   = along_warp ? nu12 : nu12 * k2 / k1;
      const double      E_xx = 0.5 * (stretch * stretch - 1.), E_yy = -nu * E_xx;
      const double      expected_force       = width * stretch * k * E_xx;
      const double      expected_contraction = width * (std::sqrt(1. + 2. * E_yy) - 1.);
      const double      force = edge_reaction_x(run.model(), run.displacement, length);
      const double      contraction = run.probe_displacement("far_corner")[1];
      const std::string along       = along_warp ? "warp" : "weft";
      check_below(pcout,
                  "strip along the " + along + ": pull " + std::to_string(force) +
                    " N against " + std::to_string(expected_force) + " N (relative)",
                  std::abs(force - expected_force) / expected_force,
                  1e-8);
      check_below(pcout,
                  "strip along the " + along + ": contraction, relative error",
                  std::abs(contraction - expected_contraction) /
                    std::abs(expected_contraction),
                  1e-8);
    }

  // 4. Bending lengths along the warp and the weft.
  for (const bool along_warp : {true, false})
    {
      const SceneRun run =
        run_scene(source_path("params/benchmarks/heavy-cantilever.prm"),
                  {"Output/Write VTK=false",
                   "Output/Progress=off",
                   "Mesh/Global refinements=1",
                   "Material/Anisotropy=orthotropic",
                   "Material/Stiffness given as=E*h",
                   "Material/Stretch stiffness=1.2e5",
                   "Material/Weft stretch stiffness=1.2e5",
                   "Material/Shear stiffness=6e4",
                   "Material/Bending=rigidity",
                   "Material/Bending rigidity=1",
                   "Material/Weft bending rigidity=0.4",
                   std::string("Material/Warp direction=") +
                     (along_warp ? "1, 0, 0" : "0, 1, 0")},
                  directory,
                  env.communicator);
      const double      deflection = -run.probe_displacement("tip")[2];
      const double      exact      = along_warp ? 0.64063 : 0.82988;
      const std::string what = along_warp ? "warp (alpha = 8)" : "weft (alpha = 20)";
      check_below(pcout,
                  "heavy cantilever along the " + what + ": tip deflection " +
                    std::to_string(deflection) + " L against " + std::to_string(exact) +
                    " L (relative)",
                  std::abs(deflection - exact) / exact,
                  3e-3);
    }

  return finish_tally(pcout);
}
