#include "physics/membrane.h"

#include "physics/sheet_stiffness.h"

#include <cmath>

namespace clothsim::physics
{
  namespace
  {
    // First fundamental form a_ab = a_a . a_b of the edge basis a_1 = x1 - x0, a_2 = x2 -
    // x0.
    struct EdgeBasis
    {
      Tensor<1, 3> a[2];
      Tensor<2, 2> metric;
    };

    EdgeBasis
    edge_basis(const TrianglePositions &x)
    {
      EdgeBasis basis;
      basis.a[0] = x[1] - x[0];
      basis.a[1] = x[2] - x[0];
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int j = 0; j < 2; ++j)
          basis.metric[i][j] = basis.a[i] * basis.a[j];
      return basis;
    }

    // Green strain E (covariant), stress S = C:E (contravariant) and energy density.
    struct StrainState
    {
      Tensor<2, 2> strain;
      Tensor<2, 2> stress;
      double       energy_density; // J/m²
    };

    StrainState
    strain_state(const MembraneStiffness &C,
                 const MembraneRestData  &rest,
                 const Tensor<2, 2>      &metric)
    {
      StrainState s;
      s.strain         = 0.5 * (metric - rest.metric); // E = (a - Ā)/2
      s.stress         = contract(C, s.strain);
      s.energy_density = 0.5 * scalar_product(s.stress, s.strain);
      return s;
    }

    // A symmetric 2x2 tensor with its eigenvalues clamped below at `floor` (<= 0).
    Tensor<2, 2>
    clamp_below(const Tensor<2, 2> &S, const double floor)
    {
      const double mean      = 0.5 * (S[0][0] + S[1][1]);
      const double half_diff = 0.5 * (S[0][0] - S[1][1]);
      const double radius    = std::sqrt(half_diff * half_diff + S[0][1] * S[0][1]);
      const double l1 = mean + radius, l2 = mean - radius;
      if (l2 >= floor)
        return S;
      Tensor<2, 2> result;
      result[0][0] = result[1][1] = floor;
      if (l1 <= floor)
        return result;
      // S' = l1 P1 + floor P2 with P1 = (S - l2 I)/(l1 - l2), P2 = I - P1.
      Tensor<2, 2> P1 = S;
      P1[0][0] -= l2;
      P1[1][1] -= l2;
      P1 /= (l1 - l2);
      result += (l1 - floor) * P1;
      return result;
    }
  } // namespace


  MembraneRestData
  membrane_rest_data(const TrianglePositions &reference)
  {
    const EdgeBasis  basis = edge_basis(reference);
    const double     det   = determinant(basis.metric);
    MembraneRestData rest;
    rest.area   = det > 0. ? 0.5 * std::sqrt(det) : 0.;
    rest.metric = basis.metric;
    if (det > 0.)
      rest.inverse_metric = invert(basis.metric);
    return rest;
  }


  MembraneStiffness
  membrane_stiffness(const MembraneMaterial  &material,
                     const TrianglePositions &reference,
                     const MembraneRestData  &rest)
  {
    return covariant_stiffness(membrane_sheet_stiffness(material.stretch_stiffness,
                                                        material.poisson_ratio,
                                                        material.weft_stretch_stiffness,
                                                        material.shear_stiffness),
                               reference,
                               rest.inverse_metric,
                               material.warp_direction);
  }


  double
  membrane_energy(const MembraneStiffness &stiffness,
                  const MembraneRestData  &rest,
                  const TrianglePositions &current)
  {
    const EdgeBasis   basis = edge_basis(current);
    const StrainState s     = strain_state(stiffness, rest, basis.metric);
    return rest.area * s.energy_density;
  }


  double
  membrane_energy_gradient_hessian(const MembraneStiffness &stiffness,
                                   const MembraneRestData  &rest,
                                   const TrianglePositions &current,
                                   const double             stress_floor,
                                   ElementVector           &gradient,
                                   ElementMatrix           *hessian,
                                   const TrianglePositions *linearised_from)
  {
    const MembraneStiffness &C     = stiffness;
    const EdgeBasis          basis = edge_basis(current);
    const StrainState        s     = strain_state(C, rest, basis.metric);
    const double             A     = rest.area;

    // f_a = dW/da_a = |T̄| S^ab a_b; x1 and x2 get f_1, f_2, x0 gets -(f_1 + f_2).
    Tensor<1, 3> f[2];
    for (unsigned int a = 0; a < 2; ++a)
      f[a] = A * (s.stress[a][0] * basis.a[0] + s.stress[a][1] * basis.a[1]);
    for (unsigned int d = 0; d < 3; ++d)
      {
        gradient[d]     = -f[0][d] - f[1][d];
        gradient[3 + d] = f[0][d];
        gradient[6 + d] = f[1][d];
      }

    if (hessian != nullptr)
      {
        // The stress of the geometric part: at x, or of the strain linearised from x_p,
        // a - Δa ⊗ Δa in the metric.
        Tensor<2, 2> S = s.stress;
        if (linearised_from != nullptr)
          {
            const EdgeBasis from   = edge_basis(*linearised_from);
            Tensor<2, 2>    metric = basis.metric;
            for (unsigned int a = 0; a < 2; ++a)
              for (unsigned int b = 0; b < 2; ++b)
                metric[a][b] -= (basis.a[a] - from.a[a]) * (basis.a[b] - from.a[b]);
            S = strain_state(C, rest, metric).stress;
          }
        const Tensor<2, 2> S_geo =
          std::isinf(stress_floor) ? S : clamp_below(S, -stress_floor);

        // Blocks H_ac = d²W/da_a da_c = |T̄| (Σ_bd C^abcd a_b ⊗ a_d + S^ac I) (3x3) for
        // a, c in {1, 2}; H_21 = H_12ᵀ (C^abcd = C^cdab). With v_d = Σ_b C^abcd a_b,
        // Σ_bd C^abcd a_b ⊗ a_d = Σ_d v_d ⊗ a_d.
        double     H[3][3][3]; // H_11, H_12, H_22
        const int  pairs[3][2] = {{0, 0}, {0, 1}, {1, 1}};
        const auto a_b         = [&basis](const unsigned int b, const unsigned int i) {
          return basis.a[b][i];
        };
        for (unsigned int p = 0; p < 3; ++p)
          {
            const unsigned int a = pairs[p][0], cc = pairs[p][1];
            double             v[2][3];
            for (unsigned int d = 0; d < 2; ++d)
              for (unsigned int i = 0; i < 3; ++i)
                v[d][i] = C[a][0][cc][d] * a_b(0, i) + C[a][1][cc][d] * a_b(1, i);
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                H[p][i][j] = A * (v[0][i] * a_b(0, j) + v[1][i] * a_b(1, j) +
                                  (i == j ? S_geo[a][cc] : 0.));
          }

        edge_basis_to_vertices(H, *hessian);
      }
    return A * s.energy_density;
  }


  MembraneStrainStress
  membrane_strain_stress(const MembraneStiffness &stiffness,
                         const MembraneRestData  &rest,
                         const TrianglePositions &current)
  {
    const EdgeBasis   basis = edge_basis(current);
    const StrainState s     = strain_state(stiffness, rest, basis.metric);
    // Mixed stress S Ā has the principal stresses as eigenvalues.
    const Tensor<2, 2>   mixed_stress = s.stress * rest.metric;
    MembraneStrainStress out;
    // tr(M²) = (Ā⁻¹ E Ā⁻¹):E.
    const Tensor<2, 2> &Q        = rest.inverse_metric;
    const double        trace_m2 = scalar_product(Q * s.strain * Q, s.strain);
    out.green_strain_norm        = std::sqrt(std::max(trace_m2, 0.));
    out.stress_norm =
      std::sqrt(std::max(scalar_product(mixed_stress, transpose(mixed_stress)), 0.));
    out.area_ratio =
      rest.area > 0.
        ? 0.5 * std::sqrt(std::max(determinant(basis.metric), 0.)) / rest.area
        : 0.;
    return out;
  }
} // namespace clothsim::physics
