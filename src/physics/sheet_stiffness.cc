#include "physics/sheet_stiffness.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace clothsim::physics
{
  SheetStiffness
  membrane_sheet_stiffness(const double warp_stretch_stiffness,
                           const double poisson_ratio,
                           const double weft_stretch_stiffness,
                           const double shear_stiffness)
  {
    const double nu = poisson_ratio, k1 = warp_stretch_stiffness;
    if (weft_stretch_stiffness == 0. && shear_stiffness == 0.)
      {
        const double coupling = k1 * nu / (1. - nu * nu), shear = k1 / (2. * (1. + nu));
        return {coupling + 2. * shear, coupling + 2. * shear, coupling, shear, true};
      }
    const double k2 = weft_stretch_stiffness;
    const double d  = 1. - nu * nu * k2 / k1; // 1 - ν_12 ν_21
    return {k1 / d, k2 / d, nu * k2 / d, shear_stiffness, false};
  }


  SheetStiffness
  bending_sheet_stiffness(const double warp_rigidity,
                          const double poisson_ratio,
                          const double weft_rigidity)
  {
    const double nu = poisson_ratio;
    if (weft_rigidity < 0.)
      {
        const double D = warp_rigidity;
        return {D, D, nu * D, 0.5 * (1. - nu) * D, true};
      }
    const double mean = std::sqrt(warp_rigidity * weft_rigidity);
    return {warp_rigidity, weft_rigidity, nu * mean, 0.5 * (1. - nu) * mean, false};
  }


  std::string
  sheet_stiffness_error(const SheetStiffness &c)
  {
    // Positive definite iff c_11 > 0, c_66 > 0 and c_11 c_22 > c_12² (bending may be 0).
    std::ostringstream message;
    if (!(c.warp >= 0. && c.weft >= 0. && c.shear >= 0.))
      message << "the warp, weft and shear stiffnesses must not be negative";
    else if (c.warp * c.weft - c.coupling * c.coupling < 0. || c.coupling < 0.)
      message << "the Poisson coupling c_12 = " << c.coupling
              << " exceeds sqrt(c_11 c_22) = " << std::sqrt(c.warp * c.weft)
              << ": the energy would not be positive (for membranes: nu_12^2 must stay "
                 "below k_warp/k_weft)";
    return message.str();
  }


  Tensor<4, 2>
  covariant_stiffness(const SheetStiffness          &c,
                      const std::array<Point<3>, 3> &reference,
                      const Tensor<2, 2>            &Q,
                      const Tensor<1, 3>            &warp)
  {
    Tensor<4, 2> C;
    if (c.isotropic)
      {
        for (unsigned int a = 0; a < 2; ++a)
          for (unsigned int b = 0; b < 2; ++b)
            for (unsigned int cc = 0; cc < 2; ++cc)
              for (unsigned int d = 0; d < 2; ++d)
                C[a][b][cc][d] = c.coupling * Q[a][b] * Q[cc][d] +
                                 c.shear * (Q[a][cc] * Q[b][d] + Q[a][d] * Q[b][cc]);
        return C;
      }

    // The material frame: the warp projected onto the triangle's plane, and n x e_1.
    const Tensor<1, 3> a1 = reference[1] - reference[0], a2 = reference[2] - reference[0];
    const Tensor<1, 3> n = cross_product_3d(a1, a2) / cross_product_3d(a1, a2).norm();
    const Tensor<1, 3> in_plane = warp - (warp * n) * n;
    if (!(in_plane.norm() > 1e-3 * warp.norm()))
      throw std::invalid_argument(
        "the warp direction is normal to the reference surface at a triangle "
        "(its part in the triangle's plane is below 1e-3 of it)");
    const Tensor<1, 3> e[2] = {in_plane / in_plane.norm(),
                               cross_product_3d(n, in_plane / in_plane.norm())};
    // R^a_i = a^a · e_i with the dual vectors a^a = Q^ab a_b.
    const Tensor<1, 3> dual[2] = {Q[0][0] * a1 + Q[0][1] * a2,
                                  Q[1][0] * a1 + Q[1][1] * a2};
    double             R[2][2];
    for (unsigned int a = 0; a < 2; ++a)
      for (unsigned int i = 0; i < 2; ++i)
        R[a][i] = dual[a] * e[i];

    // The frame's c_ijkl: c_1111, c_2222, c_1122 = c_2211, c_1212 = c_1221 = c_2112 =
    // c_2121.
    double frame[2][2][2][2] = {};
    frame[0][0][0][0]        = c.warp;
    frame[1][1][1][1]        = c.weft;
    frame[0][0][1][1] = frame[1][1][0][0] = c.coupling;
    frame[0][1][0][1] = frame[0][1][1][0] = frame[1][0][0][1] = frame[1][0][1][0] =
      c.shear;
    for (unsigned int a = 0; a < 2; ++a)
      for (unsigned int b = 0; b < 2; ++b)
        for (unsigned int cc = 0; cc < 2; ++cc)
          for (unsigned int d = 0; d < 2; ++d)
            {
              double sum = 0.;
              for (unsigned int i = 0; i < 2; ++i)
                for (unsigned int j = 0; j < 2; ++j)
                  for (unsigned int k = 0; k < 2; ++k)
                    for (unsigned int l = 0; l < 2; ++l)
                      sum += frame[i][j][k][l] * R[a][i] * R[b][j] * R[cc][k] * R[d][l];
              C[a][b][cc][d] = sum;
            }
    return C;
  }


  Tensor<2, 2>
  contract(const Tensor<4, 2> &C, const Tensor<2, 2> &M)
  {
    Tensor<2, 2> S;
    for (unsigned int a = 0; a < 2; ++a)
      for (unsigned int b = 0; b < 2; ++b)
        S[a][b] = C[a][b][0][0] * M[0][0] + C[a][b][0][1] * M[0][1] +
                  C[a][b][1][0] * M[1][0] + C[a][b][1][1] * M[1][1];
    return S;
  }
} // namespace clothsim::physics
