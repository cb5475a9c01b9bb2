#pragma once

// Bending energy of a thin shell: the midedge-director shell (Grinspun, Gingold, Reisman
// & Zorin, "Computing discrete shape operators on general meshes", Eurographics 2006;
// Γ-convergence on general meshes: Degrooff, Gladbach & Olbermann 2023, arXiv
// 2302.01705). Positions are P1; every edge E carries one director d_E, a unit vector
// perpendicular to the edge, parametrised by one angle ψ_E. For small deflections this is
// the Morley plate element. See ../shared/BENDING.md for why this discretisation (and not
// hinge angles or averaged normals) converges on unstructured meshes.
//
// Per triangle with vertices x0, x1, x2 (consistently oriented), indices mod 3:
//   edge i opposite vertex i  e_i = x_{i+2} - x_{i+1},  ℓ_i = |e_i|
//   unnormalised normal       N = (x1 - x0) × (x2 - x0),  n = N / |N|
//   altitude                  h_i = |N| / ℓ_i
//   outward co-normal         μ_i = e_i × n / ℓ_i
//   director tilt             δ_i = atan2(r_i·μ_i, r_i·n) + s_i ψ_i   (mod 2π, in [-π,
//   π])
// where r_i is the edge's reference vector (the director at ψ = 0; only its part normal
// to the edge matters, so δ_i = atan2(N·(r_i × e_i)/ℓ_i, N·r_i) needs no projection) and
// s_i = ±1 says whether the edge's global direction is e_i (+1) or -e_i (-1): rotating
// the director by +ψ about the globally oriented edge tilts it by s_i ψ towards μ_i. Each
// element thus needs only its own 3 vertices and 3 edge angles (12 unknowns; chart B of
// BENDING.md). The reference vectors are re-based on the current directors after every
// converged step (ψ -> 0), so the chart never approaches its singularity (r_i ∥ e_i).
//
//   edge curvature            II_i = 2 h_i f(δ_i),  f = id, sin or tan
//   second fundamental form   b = [[II_0 + II_1, II_0], [II_0, II_0 + II_2]]
//                             in the basis a_1 = x1 - x0, a_2 = x2 - x0
//   (b = Σ_i (2 δ_i / h_i) (a_α·μ_i)(a_β·μ_i) for f = id: the gradient of the
//   Crouzeix–Raviart interpolant of the midedge normals)
//   energy                    W = |T̄| D/2 [ ν (tr M)² + (1-ν) tr(M²) ],
//                             M = Ā⁻¹ (b - B̄)  (curvature change, 1/m);
//                             orthotropic (warp and weft rigidities D_1, D_2; Huber's
//                             plate, physics/sheet_stiffness.h): W = |T̄|/2 C^abcd
//                             (b - B̄)_ab (b - B̄)_cd
// with Ā, B̄ the same forms on the reference mesh with its rest directors (ψ̄ = 0 and r
// on the bisector of the two rest normals, or the rest normal on a boundary edge), and D
// the bending rigidity (E h³ / (12 (1-ν²)) for an elastic plate). Since b is linear in
// II, W = ½ (II - ĪI)ᵀ C (II - ĪI) with a constant 3×3 matrix C per element:
//   gradient   ∇W  = Σ_i [C (II - ĪI)]_i ∇II_i
//   Hessian    ∇²W = Σ_ik C_ik ∇II_i ∇II_kᵀ + Σ_i [C (II - ĪI)]_i ∇²II_i
// The first part (Gauss–Newton) is positive semi-definite; the tangent may use it alone.
// The position derivatives of h_i and atan2(...) come from forward-mode automatic
// differentiation (Sacado, second order) in the 6 edge-vector coordinates a_1, a_2 (both
// are translation invariant), mapped to the 9 vertex coordinates; the ψ derivatives are
// closed form. Cost (one core): about 6 µs per triangle for the exact Hessian, 0.6 µs for
// the gradient with the Gauss–Newton Hessian.

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include "physics/membrane.h"

#include <array>

namespace clothsim::physics
{
  using namespace dealii;

  // f in II_i = 2 h_i f(δ_i): 'angle' (f = id), 'sine', 'tangent' (f = tan δ: a barrier
  // at |δ| = π/2, against folding an element flat onto its neighbour), 'half tangent'
  // (f = 2 tan(δ/2) = δ + δ³/12 + ...: a barrier at |δ| = π, against a crease turning
  // inside out, its two triangles passing through each other).
  enum class DirectorFunction
  {
    angle,
    sine,
    tangent,
    half_tangent
  };

  // The tilt at which f has its barrier (π/2 for 'tangent', π for 'half tangent'), or 0
  // if f has none. Newton's line search must not carry a tilt across it
  // (tilt_step_bound).
  double
  barrier_tilt(const DirectorFunction function);

  struct BendingMaterial
  {
    double           rigidity;      // D, N·m (orthotropic: D_1, along the warp)
    double           poisson_ratio; // ν, 0 <= ν < 0.5
    DirectorFunction director_function;
    double           weft_rigidity  = -1.;            // D_2, N·m; negative: isotropic
    Tensor<1, 3>     warp_direction = Tensor<1, 3>(); // in space (orthotropic only)
  };

  // The three edges of one triangle as the triangle sees them; edge i is opposite vertex
  // i.
  struct EdgeDirectors
  {
    std::array<Tensor<1, 3>, 3> reference; // r_i, the director at ψ_i = 0 (unit)
    std::array<double, 3>       sign;      // s_i = ±1 (see the file comment)
  };

  using EdgeAngles = std::array<double, 3>; // ψ_i, rad

  // What the rest state of one triangle contributes, computed once.
  struct BendingRestData
  {
    std::array<std::array<double, 3>, 3> stiffness;           // C, N/m (J per m² of II)
    std::array<double, 3>                rest_edge_curvature; // ĪI_i, m
    Tensor<2, 2>                         inverse_metric;      // Ā⁻¹, 1/m²
  };

  // 12 local unknowns: x0, x1, x2 (x, y, z each; 9), then ψ0, ψ1, ψ2.
  using BendingVector = std::array<double, 12>;
  using BendingMatrix = std::array<std::array<double, 12>, 12>;

  // Rest data from the reference positions and the rest directors (ψ̄ = 0). Throws
  // std::invalid_argument for an orthotropic material whose warp is normal to the
  // triangle.
  BendingRestData
  bending_rest_data(const BendingMaterial   &material,
                    const TrianglePositions &reference,
                    const EdgeDirectors     &rest_directors);

  // The tilts δ_i (rad) of the three edge directors against the triangle's normal.
  std::array<double, 3>
  director_tilts(const TrianglePositions &x,
                 const EdgeDirectors     &directors,
                 const EdgeAngles        &psi);

  // The largest α <= `alpha` (halved from it, at most 30 times; 0 if none) for which the
  // triangle moved from (x, ψ) to (x + α dx, ψ + α dψ) keeps every tilt δ_i on its branch
  // of f: δ_i, followed continuously from α = 0 through α/4, α/2, 3α/4 to α, changes by
  // at most π/2 between samples (which rules out a wrap) and stays within 9/10 of the way
  // to the barrier b: |δ_i| <= |δ_i(0)| + 0.9 (b - |δ_i(0)|) at every sample (not bounded
  // in between). A tilt already at or past b has no branch to keep and is not checked.
  // Returns `alpha` for a function without barrier.
  double
  tilt_step_bound(const DirectorFunction             function,
                  const TrianglePositions           &x,
                  const std::array<Tensor<1, 3>, 3> &dx,
                  const EdgeDirectors               &directors,
                  const EdgeAngles                  &psi,
                  const EdgeAngles                  &dpsi,
                  double                             alpha);

  // Energy W (J) of one triangle.
  double
  bending_energy(const BendingMaterial   &material,
                 const BendingRestData   &rest,
                 const TrianglePositions &x,
                 const EdgeDirectors     &directors,
                 const EdgeAngles        &psi);

  // Energy, gradient (N for positions, N·m for angles; ordered as BendingVector) and, if
  // non-null, the Hessian: exact, or only its Gauss–Newton part (PSD) if `gauss_newton`.
  double
  bending_energy_gradient_hessian(const BendingMaterial   &material,
                                  const BendingRestData   &rest,
                                  const TrianglePositions &x,
                                  const EdgeDirectors     &directors,
                                  const EdgeAngles        &psi,
                                  const bool               gauss_newton,
                                  BendingVector           &gradient,
                                  BendingMatrix           *hessian);

  // Norm sqrt(tr(M²)) of the curvature change M = Ā⁻¹ (b - B̄), 1/m (for output).
  double
  curvature_change_norm(const BendingMaterial   &material,
                        const BendingRestData   &rest,
                        const TrianglePositions &x,
                        const EdgeDirectors     &directors,
                        const EdgeAngles        &psi);

  // The unit director of an edge from its end points in global order, its reference
  // vector r and angle ψ: r's part normal to the edge, rotated by ψ about the edge.
  Tensor<1, 3>
  edge_director(const Point<3>     &first,
                const Point<3>     &second,
                const Tensor<1, 3> &reference,
                const double        psi);
} // namespace clothsim::physics
