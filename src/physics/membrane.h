#pragma once

// Membrane energy of a thin sheet: plane-stress St. Venant–Kirchhoff (isotropic or
// orthotropic, physics/sheet_stiffness.h) on the Green strain of the surface, on linear
// (3-node) triangles. Pure functions: rest data +
// current vertex positions -> energy, gradient, Hessian. Assembly and constraints live
// elsewhere.
//
// Per triangle with reference vertices X0, X1, X2 and current x0, x1, x2:
//   covariant basis        a_1 = x1 - x0,  a_2 = x2 - x0   (Ā from the reference
//   vertices) first fundamental form a_ab = a_a . a_b Green strain           E_ab = (a_ab
//   - Ā_ab) / 2,   M = Ā⁻¹ E  (mixed, eigenvalues are the
//                                                      principal Green strains)
//   energy                 W = |T̄|/2 C^abcd E_ab E_cd, isotropic:
//                          W = |T̄| k [ λ'/2 (tr M)² + μ' tr(M²) ],  λ' = ν/(1-ν²),
//                          μ' = 1/(2(1+ν)), C^abcd = k [ λ' Q^ab Q^cd + μ' (Q^ac Q^bd +
//                          Q^ad Q^bc) ], Q = Ā⁻¹
// with k = E h the stretch stiffness in N/m (Ciarlet, "Mathematical Elasticity III", ch.
// 4; the membrane part of the Koiter energy, Terzopoulos et al. 1987's ||G - G⁰||²); an
// orthotropic sheet has its own C per triangle (physics/sheet_stiffness.h), precomputed.
//   2nd Piola-Kirchhoff stress resultant (contravariant, N/m)
//                          S^ab = C^abcd E_cd
//   gradient               dW/da_a = |T̄| S^ab a_b
//   Hessian                d²W/da_a da_c = |T̄| [ S^ac I + C^abcd a_b ⊗ a_d ].
// The material part (C) is positive semi-definite for a positive definite law; the
// geometric part S^ac I is indefinite under compression. The tangent can clamp the
// eigenvalues of the matrix S^ac from below at -s_min (s_min >= 0, N/m): s_min = 0 gives
// a positive semi-definite element Hessian (a tension-field tangent), s_min = ∞ the exact
// one. Since the geometric block is |T̄| (B S Bᵀ) ⊗ I with B the 3x2 vertex weights (|B|²
// = 3), clamping at -s_min = -m_min / (3 |T̄|) keeps geometric + m_min I positive
// semi-definite: a time step's mass term pays for the compression, and Newton stays exact
// wherever it can (see ClothModel). Mixed-stress tangent (the "mixed integration point"
// Newton of Magisano, Leonetti & Garcea, Int. J. Numer. Meth. Eng. 109, 2017): Newton on
// the mixed form (x, S) with S eliminated per element takes the residual at x but the
// geometric stiffness from the stress of the strain linearised from the previous
// linearisation point x_p,
//   E_lin = E(x) - ½ Δa_a·Δa_b,   Δa = a(x) - a(x_p)   (E is quadratic in a).
// A stiff membrane turning within an iteration no longer stiffens the tangent with the
// spurious stretch of the linearised rotation, and Newton needs fewer iterations.

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>

namespace clothsim::physics
{
  using namespace dealii;

  // Membrane material: isotropic (k, ν), or orthotropic (k_1 = k along the warp, k_2
  // along the weft, shear g, ν_12) when the weft or shear stiffness is set.
  struct MembraneMaterial
  {
    double       stretch_stiffness;          // k = E h (orthotropic: k_1), N/m
    double       poisson_ratio;              // ν (orthotropic: ν_12), dimensionless
    double       weft_stretch_stiffness = 0; // k_2 = E_2 h, N/m; 0 and g 0: isotropic
    double       shear_stiffness        = 0; // g = G_12 h, N/m
    Tensor<1, 3> warp_direction         = Tensor<1, 3>(); // in space (orthotropic only)
  };

  // C^abcd of the material for one triangle (N/m⁵; physics/sheet_stiffness.h): what
  // the kernels below take as `stiffness`.
  using MembraneStiffness = Tensor<4, 2>;

  // What the rest state of one triangle contributes, computed once.
  struct MembraneRestData
  {
    Tensor<2, 2> metric;         // Ā, m²
    Tensor<2, 2> inverse_metric; // Ā⁻¹, 1/m²
    double       area;           // |T̄|, m²
  };

  using TrianglePositions = std::array<Point<3>, 3>;
  using ElementVector     = std::array<double, 9>;
  using ElementMatrix     = std::array<std::array<double, 9>, 9>;

  // The chain rule from the edge basis a_1 = x1 - x0, a_2 = x2 - x0 to the vertices: a
  // Hessian given by its 3 x 3 blocks H_11, H_12, H_22 in (a_1, a_2) (H_21 = H_12ᵀ) is,
  // in the vertices (weights w_0 = (-1, -1), w_1 = (1, 0), w_2 = (0, 1)), K_11 = H_11,
  // K_12 = H_12, K_22 = H_22, K_10 = -(H_11 + H_12), K_20 = -(H_21 + H_22), K_00 = H_11
  // + H_12 + H_21 + H_22 and K_uv = K_vuᵀ: written to rows and columns 0-8 of K.
  template <class Matrix>
  void
  edge_basis_to_vertices(const double (&H)[3][3][3], Matrix &K)
  {
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          const double h11 = H[0][i][j], h12 = H[1][i][j], h21 = H[1][j][i],
                       h22 = H[2][i][j];
          K[3 + i][3 + j]  = h11;
          K[3 + i][6 + j]  = h12;
          K[6 + i][3 + j]  = h21;
          K[6 + i][6 + j]  = h22;
          K[3 + i][j] = K[j][3 + i] = -(h11 + h12);
          K[6 + i][j] = K[j][6 + i] = -(h21 + h22);
          K[i][j]                   = h11 + h12 + h21 + h22;
        }
  }

  // Rest data from the reference positions. Returns area 0 for a degenerate triangle.
  MembraneRestData
  membrane_rest_data(const TrianglePositions &reference);

  // The material's C^abcd on one reference triangle (throws std::invalid_argument for
  // an orthotropic material whose warp is normal to the triangle).
  MembraneStiffness
  membrane_stiffness(const MembraneMaterial  &material,
                     const TrianglePositions &reference,
                     const MembraneRestData  &rest);

  // Energy W (J) of one triangle.
  double
  membrane_energy(const MembraneStiffness &stiffness,
                  const MembraneRestData  &rest,
                  const TrianglePositions &current);

  // Energy, gradient dW/dx (N, ordered x0.x, x0.y, x0.z, x1.x, ...) and Hessian d²W/dx²
  // (N/m). `hessian` may be null when only the gradient is needed. The Hessian's
  // geometric part uses S with eigenvalues clamped below at -stress_floor (N/m; infinity:
  // exact Hessian); with `linearised_from` (x_p), the S of the strain linearised from
  // there (the mixed-stress tangent above; x_p = current: the Hessian).
  double
  membrane_energy_gradient_hessian(const MembraneStiffness &stiffness,
                                   const MembraneRestData  &rest,
                                   const TrianglePositions &current,
                                   const double             stress_floor,
                                   ElementVector           &gradient,
                                   ElementMatrix           *hessian,
                                   const TrianglePositions *linearised_from = nullptr);

  // Strain and stress measures of one triangle for output.
  struct MembraneStrainStress
  {
    double green_strain_norm; // sqrt(tr(M²)), dimensionless
    double stress_norm;       // sqrt(tr((S Ā)²)), N/m
    double area_ratio; // |T| / |T̄|; <= 0 never happens for a surface, but 0 = collapsed
  };

  MembraneStrainStress
  membrane_strain_stress(const MembraneStiffness &stiffness,
                         const MembraneRestData  &rest,
                         const TrianglePositions &current);
} // namespace clothsim::physics
