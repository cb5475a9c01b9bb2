#pragma once

// Provot mass-spring reference model (X. Provot, "Deformation constraints in a
// mass-spring model to describe rigid cloth behavior", Graphics Interface 1995): the
// spring kernel, spring constants derived from the continuum parameters, and Provot's
// strain limit. Pure functions; assembly lives elsewhere.
//
// One spring between x0 and x1, rest length L, stiffness k (N/m):
//   d = x1 - x0,  ℓ = |d|,  u = d / ℓ
//   energy      W = ½ k (ℓ - L)²
//   gradient    dW/dx1 = -dW/dx0 = k (ℓ - L) u
//   Hessian     d²W/dx1² = K,  d²W/dx0 dx1 = -K,
//               K = k [ u ⊗ u + (1 - L/ℓ) (I - u ⊗ u) ]
// The transverse part (1 - L/ℓ) is negative under compression (ℓ < L); the projected
// Hessian drops it there (K = k u ⊗ u), which leaves the 6×6 matrix positive
// semi-definite (Choi & Ko, "Stable but responsive cloth", SIGGRAPH 2002).
//
// Spring constants from the continuum (k_m = E h stretch stiffness, ν, D bending
// rigidity). The Etzmuss–Gross–Strasser (TVCG 2003) text was not available to us: the
// constants below are OUR derivation by energy equivalence, small strain, flat rest
// state.
//
// Structural springs (one per mesh edge e, rest length L_e, adjacent rest triangles T):
//   k_e = c(ν) k_m Σ_{T ∋ e} |T| / L_e²,   c(ν) = 8 / (9 (1 - ν²))            (*)
// Derivation: a triangle whose three edges carry springs k_T,i = k_m |T| / L_i² has, for
// a homogeneous small strain ε, energy Σ_i ½ k_T,i L_i² (t_i·ε·t_i)². On an equilateral
// triangle Σ_i (t_i·ε·t_i)² = (3/8) [(tr ε)² + 2 ε:ε], so the energy is
// |T| k_m (3/16) [(tr ε)² + 2 ε:ε], which is exactly the continuum energy
// |T| k_m [λ'/2 (tr ε)² + μ' ε:ε] (membrane.h) iff λ' = μ', i.e. ν = 1/3: a central-force
// lattice has λ = μ (Cauchy relation) and can represent no other ν. The per-triangle
// split is exact, so boundary edges (one triangle) get half the interior value.
// Equilateral lattice: k_e = (√3/2) k_m at ν = 1/3 (equivalently the lattice's Young
// modulus is (2/√3) k_e; NOT k_e = (2/√3) E h). For ν ≠ 1/3 the factor c(ν) makes the
// equilateral lattice's uniaxial-strain (laterally constrained) stiffness
// C11 = (3√3/4) k_e equal the continuum's k_m / (1 - ν²), i.e. the lattice's longitudinal
// wave speed √(C11/ρ) equals the continuum's, in the spirit of Hauth & Etzmuss
// (Eurographics 2001). The lattice keeps Poisson ratio 1/3, and its shear modulus is
// 2 / (3 (1 - ν)) times the continuum's (2/3 at ν = 0, 1.21 at ν = 0.45).
// Generalisation to unstructured meshes: the area weighting |T|/L² is Van Gelder's
// ("Approximate simulation of elastic membranes by triangulated spring meshes", J.
// Graphics Tools 3(2), 1998), exact only on equilateral triangles; on other triangles no
// spring assignment reproduces the continuum (Van Gelder).
//
// Bend springs (between the two vertices opposite an interior edge e of length L_e with
// adjacent rest areas A1, A2, spring rest length L_b). Reference: the hinge energy
//   W_e = c_e θ²,  c_e = D L_e² / (2 (A1 + A2))                                (**)
// with θ the fold angle between the two triangles. Derivation (equilateral lattice, small
// deflection w = ½ Xᵀ b X, vertices on the surface): the fold across an edge with unit
// in-plane normal n and tangent t is θ_e = (L/√3) [ (3/2) n·b·n - (1/2) t·b·t ] (the
// second term is the P1 interpolation error), and summing over the three edge directions
// (1/(2|T|) edges per unit area each) gives the density (c_e L² / (6|T|)) (3/4)
// [4 b:b - (tr b)²]. This equals the plate's D/2 [ν (tr b)² + (1-ν) b:b] for cylindrical
// bending (D/2 κ², any direction, any ν) with (**), but for doubly curved b it is the
// plate with ν = -1/3: against a plate of ratio ν the hinge has 2/(3(1+ν)) of its energy
// in spherical and 4/(3(1-ν)) in saddle bending (1/2 and 2 at ν = 1/3). Test-verified.
// Limit: a bend spring whose rest length is the FLAT distance has zero linear bending
// stiffness: folding by θ shortens it by
// ΔL = 2 h1 h2 (1 - cos θ) / (L_b + ℓ) ≈ h1 h2 θ² / (2 L_b) (h_i = 2 A_i / L_e the
// altitudes), so its energy is ½ k ΔL² ∝ θ⁴. No constant k reproduces a plate at small
// deflections. We therefore match the hinge energy (secant) at a chosen reference fold
// angle θ_r, exactly:
//   k_b = 2 c_e θ_r² / ΔL(θ_r)²  ≈ 8 c_e L_b² / (h1² h2² θ_r²)
// so the spring is softer than the plate for |θ| < θ_r (energy ratio (θ/θ_r)²) and
// stiffer beyond; it also adds in-plane stiffness (k_b / k_e ~ (h/L)² / θ_r², small for
// thin sheets). Valid only for flat rest states.
//
// Large strain: a spring's force is linear in its stretch ℓ - L, the St. Venant–Kirchhoff
// membrane's stress linear in the Green strain ε + ε²/2, so under uniaxial stretch the
// membrane's force per width grows like ε (1 + 3ε/2 + ...) against the springs' ε: the
// constants above hold for small strain only (about 15 % apart at 10 % strain).
//
// Strain limit (Provot 1995): a spring longer than (1 + τ) L (optionally shorter than
// (1 - τ) L) is brought back to that length by moving both ends along u, in proportion to
// their inverse masses w0, w1 (0 = pinned): the mass-weighted centre stays put.

#include <deal.II/base/point.h>

#include <array>

namespace clothsim::physics
{
  using namespace dealii;

  struct Spring
  {
    double stiffness;   // k, N/m
    double rest_length; // L, m
  };

  using SpringPositions = std::array<Point<3>, 2>;
  using SpringVector    = std::array<double, 6>;
  using SpringMatrix    = std::array<std::array<double, 6>, 6>;

  // Energy W (J) of one spring.
  double
  spring_energy(const Spring &spring, const SpringPositions &x);

  // Energy, gradient dW/dx (N, ordered x0.x, x0.y, x0.z, x1.x, ...) and Hessian d²W/dx²
  // (N/m). `hessian` may be null. `project`: drop the transverse part under compression
  // (positive semi-definite). At ℓ = 0 the direction is undefined: gradient and Hessian
  // are returned as zero.
  double
  spring_energy_gradient_hessian(const Spring          &spring,
                                 const SpringPositions &x,
                                 const bool             project,
                                 SpringVector          &gradient,
                                 SpringMatrix          *hessian);

  // c(ν) k_m Σ_T |T| / L², see (*). area_2 = 0 for a boundary edge. N/m.
  double
  structural_spring_stiffness(const double stretch_stiffness, // k_m = E h, N/m
                              const double poisson_ratio,
                              const double rest_length, // L_e, m
                              const double area_1,      // m²
                              const double area_2);     // m², 0 on the boundary

  // c_e of (**), the hinge coefficient (J per rad²) of an interior edge.
  double
  hinge_bending_coefficient(const double rigidity,    // D, N·m
                            const double edge_length, // L_e, m
                            const double area_1,
                            const double area_2);

  // k_b matching the hinge energy c_e θ_r² exactly at the fold angle θ_r (flat rest).
  // N/m.
  double
  bend_spring_stiffness(const double rigidity,         // D, N·m
                        const double edge_length,      // L_e, m
                        const double area_1,           // m²
                        const double area_2,           // m²
                        const double bend_rest_length, // L_b, flat distance, m
                        const double reference_angle); // θ_r, rad, > 0

  // Provot's strain limit: the corrected end positions. Strain (ℓ - L) / L is capped at
  // +limit (and at -limit if `limit_compression`); unchanged if compliant, if both ends
  // are pinned (w0 = w1 = 0), or if ℓ = 0.
  SpringPositions
  limit_strain(const SpringPositions &x,
               const double           rest_length,
               const double           limit, // τ, e.g. 0.1
               const double           inverse_mass_0,
               const double           inverse_mass_1,
               const bool             limit_compression = false);
} // namespace clothsim::physics
