#pragma once

// The constitutive tensor of a thin sheet, isotropic or orthotropic (woven cloth: warp
// and weft stiff, bias soft), in a triangle's covariant basis. Membrane and bending share
// it: both energies are W = |T̄|/2 C^abcd M_ab M_cd of a symmetric 2x2 measure M in the
// basis a_1 = X1 - X0, a_2 = X2 - X0 (Green strain E, N/m; curvature change b - B̄, N·m).
//
// In the material frame (e_1 along the warp, e_2 along the weft, orthonormal in the
// reference surface) an orthotropic sheet has four constants (Voigt: c_11, c_22, c_12 =
// c_1122, c_66 = c_1212):
//   W/|T̄| = ½ c_11 M_11² + c_12 M_11 M_22 + ½ c_22 M_22² + 2 c_66 M_12².
//   membrane (plane stress, Jones, "Mechanics of Composite Materials", 2nd ed., §2.6),
//     k_1 = E_1 h, k_2 = E_2 h, g = G_12 h (N/m), ν_12 (weft contraction per warp
//     stretch), ν_21 = ν_12 k_2 / k_1, d = 1 - ν_12 ν_21 > 0:
//     c_11 = k_1/d, c_22 = k_2/d, c_12 = ν_12 k_2/d, c_66 = g;
//     isotropic: k_1 = k_2 = k, g = k / (2(1+ν)).
//   bending (Huber's orthotropic plate, 1923: the usual closure when only the two
//     rigidities are measured, as by the Kawabata and cantilever tests), D_1, D_2 (N·m):
//     c_11 = D_1, c_22 = D_2, c_12 = ν sqrt(D_1 D_2), c_66 = (1-ν) sqrt(D_1 D_2) / 2;
//     isotropic: D_1 = D_2 = D, the plate rigidity.
// A uniaxial stress along an angle θ from the warp meets the compliance (membrane; the
// closed form the tests check)
//   1/k(θ) = cos⁴θ/k_1 + (1/g - 2 ν_12/k_1) sin²θ cos²θ + sin⁴θ/k_2.
// In the covariant basis, with the dual vectors a^a = Ā^ab a_b and R^a_i = a^a · e_i:
//   C^abcd = c_ijkl R^a_i R^b_j R^c_k R^d_l,
// which for an isotropic sheet is c_12 Ā^ab Ā^cd + c_66 (Ā^ac Ā^bd + Ā^ad Ā^bc), needing
// no frame. The warp is given as a direction in space and projected onto each reference
// triangle's plane (for a flat or gently curved sheet, the fabric's grain).

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <string>

namespace clothsim::physics
{
  using namespace dealii;

  // The material-frame constants c_11, c_22, c_12, c_66 (N/m for membranes, N·m for
  // bending), and whether they are isotropic (then c_11 = c_22 = c_12 + 2 c_66 and the
  // frame is not used).
  struct SheetStiffness
  {
    double warp;     // c_11
    double weft;     // c_22
    double coupling; // c_12
    double shear;    // c_66
    bool   isotropic;
  };

  // Plane-stress membrane: stretch stiffnesses k_1 (warp), k_2 (weft) and shear
  // stiffness g in N/m, Poisson ratio ν_12. Isotropic when k_2 = 0 and g = 0: then k_1
  // = k, g = k/(2(1+ν)).
  SheetStiffness
  membrane_sheet_stiffness(const double warp_stretch_stiffness,
                           const double poisson_ratio,
                           const double weft_stretch_stiffness,
                           const double shear_stiffness);

  // Bending (Huber): rigidities D_1 (warp), D_2 (weft) in N·m, Poisson ratio ν.
  // Isotropic when D_2 < 0 (then D_2 = D_1).
  SheetStiffness
  bending_sheet_stiffness(const double warp_rigidity,
                          const double poisson_ratio,
                          const double weft_rigidity);

  // Why constants are not a positive definite orthotropic law, or empty if they are.
  std::string
  sheet_stiffness_error(const SheetStiffness &stiffness);

  // C^abcd (units of the constants, per m⁴ of the basis) of one reference triangle;
  // `warp` in space, not normal to the triangle (an isotropic sheet ignores it). Throws
  // std::invalid_argument if the warp's part in the triangle's plane is below 1e-3 of it.
  Tensor<4, 2>
  covariant_stiffness(const SheetStiffness          &stiffness,
                      const std::array<Point<3>, 3> &reference,
                      const Tensor<2, 2>            &inverse_metric,
                      const Tensor<1, 3>            &warp);

  // C^abcd M_cd: the stress (or moment) of a measure M in the covariant basis.
  Tensor<2, 2>
  contract(const Tensor<4, 2> &stiffness, const Tensor<2, 2> &measure);
} // namespace clothsim::physics
