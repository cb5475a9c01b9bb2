#include "physics/bending.h"

#include "physics/sheet_stiffness.h"

#include <Sacado.hpp>

#include <cmath>

namespace clothsim::physics
{
  namespace
  {
    // The tilt δ = φ + s ψ is an angle between two directions, defined modulo 2π: its
    // principal value in [-π, π]. φ alone (atan2) jumps by 2π when a face turns half a
    // revolution against its edge's reference vector within one step (a fold rolling
    // through the material; measured on the swinging sheet: ψ = -2.3 rad with φ at π
    // made the energy jump by 7e-4 J at the Newton iterate and the line search fail).
    // δ stays continuous unless the director itself points straight through the face.
    // (std::remainder returns a value already in [-π, π] unchanged; skipping the call
    // there gives the same bits, and it was 2.7 % of the swinging sheet's run.)
    double
    principal_tilt(const double tilt)
    {
      return std::abs(tilt) <= numbers::PI ? tilt
                                           : std::remainder(tilt, 2. * numbers::PI);
    }

    // f, f', f'' of the director function at δ (any branch: δ is reduced first).
    struct DirectorFunctionValues
    {
      double value, first, second;
    };

    DirectorFunctionValues
    evaluate(const DirectorFunction function, const double tilt)
    {
      const double delta = principal_tilt(tilt);
      switch (function)
        {
          case DirectorFunction::angle:
            return {delta, 1., 0.};
          case DirectorFunction::sine:
            return {std::sin(delta), std::cos(delta), -std::sin(delta)};
            case DirectorFunction::tangent: {
              const double t = std::tan(delta);
              return {t, 1. + t * t, 2. * t * (1. + t * t)};
            }
            case DirectorFunction::half_tangent: {
              // f = 2 tan(δ/2), f' = 1 + t², f'' = t (1 + t²) with t = tan(δ/2).
              const double t = std::tan(0.5 * delta);
              return {2. * t, 1. + t * t, t * (1. + t * t)};
            }
        }
      return {0., 0., 0.};
    }

    template <typename Number>
    using Vec3 = std::array<Number, 3>;

    template <typename Number>
    Vec3<Number>
    cross(const Vec3<Number> &a, const Vec3<Number> &b)
    {
      return {{a[1] * b[2] - a[2] * b[1],
               a[2] * b[0] - a[0] * b[2],
               a[0] * b[1] - a[1] * b[0]}};
    }

    // Altitudes h_i = |N|/ℓ_i and the position parts of the tilts, φ_i =
    // atan2(N·(r_i × e_i)/ℓ_i, N·r_i), from the 9 vertex coordinates.
    template <typename Number>
    void
    edge_geometry(const std::array<Number, 9>       &x,
                  const std::array<Tensor<1, 3>, 3> &reference,
                  std::array<Number, 3>             &altitude,
                  std::array<Number, 3>             &tilt)
    {
      Vec3<Number> a1, a2;
      for (unsigned int d = 0; d < 3; ++d)
        {
          a1[d] = x[3 + d] - x[d];
          a2[d] = x[6 + d] - x[d];
        }
      const Vec3<Number> N = cross(a1, a2);
      using std::sqrt, std::atan2;
      const Number norm_N = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
      for (unsigned int i = 0; i < 3; ++i)
        {
          const unsigned int j = (i + 1) % 3, k = (i + 2) % 3;
          Vec3<Number>       e;
          for (unsigned int d = 0; d < 3; ++d)
            e[d] = x[3 * k + d] - x[3 * j + d];
          const Number        length = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
          const Tensor<1, 3> &r      = reference[i];
          // r × e (linear in x), then N·(r × e) and N·r.
          const Vec3<Number> r_cross_e   = {{r[1] * e[2] - r[2] * e[1],
                                             r[2] * e[0] - r[0] * e[2],
                                             r[0] * e[1] - r[1] * e[0]}};
          const Number       normal_part = N[0] * r[0] + N[1] * r[1] + N[2] * r[2];
          const Number       conormal_part =
            (N[0] * r_cross_e[0] + N[1] * r_cross_e[1] + N[2] * r_cross_e[2]) / length;
          altitude[i] = norm_N / length;
          tilt[i]     = atan2(conormal_part, normal_part);
        }
    }

    // edge_geometry's h_i and φ_i with their gradients in a_1 = x_1 - x_0 and
    // a_2 = x_2 - x_0 (rows 0-2 and 3-5), by hand: with N = a_1 × a_2, e_i the edge, ℓ_i
    // its length, n_i = N·r_i, c_i = N·(r_i × e_i)/ℓ_i, and ∇_{a_1} (w·N) = a_2 × w,
    // ∇_{a_2} (w·N) = w × a_1 for a fixed w:
    //   ∇h = ∇|N|/ℓ − h ∇ℓ/ℓ,   ∇φ = (n ∇c − c ∇n)/(n² + c²),
    //   ∇c = [∇(N·(r × e)) + (N × r) ∇e − c ∇ℓ]/ℓ,   ∇ℓ = (e/ℓ) ∇e.
    // (Checked against the automatic differentiation of edge_geometry by
    // tests/bending_derivatives. The bending term's assembly on the swinging sheet took
    // 27 % less time than with that differentiation: README, "Bending gradient by hand".)
    void
    edge_geometry_gradient(const std::array<double, 6>          &a,
                           const std::array<Tensor<1, 3>, 3>    &reference,
                           std::array<double, 3>                &altitude,
                           std::array<double, 3>                &tilt,
                           std::array<std::array<double, 6>, 3> &d_altitude,
                           std::array<std::array<double, 6>, 3> &d_tilt)
    {
      const Vec3<double> a1 = {{a[0], a[1], a[2]}}, a2 = {{a[3], a[4], a[5]}};
      const Vec3<double> N        = cross(a1, a2);
      const double       norm_N   = std::sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
      const Vec3<double> unit_N   = {{N[0] / norm_N, N[1] / norm_N, N[2] / norm_N}};
      const Vec3<double> d_norm_1 = cross(a2, unit_N), d_norm_2 = cross(unit_N, a1);
      // e_0 = a_2 − a_1, e_1 = −a_2, e_2 = a_1: ∂e_i/∂a_1 and ∂e_i/∂a_2 (times I).
      constexpr double e_1[3] = {-1., 0., 1.}, e_2[3] = {1., -1., 0.};
      for (unsigned int i = 0; i < 3; ++i)
        {
          Vec3<double> e, r;
          for (unsigned int d = 0; d < 3; ++d)
            {
              e[d] = e_1[i] * a1[d] + e_2[i] * a2[d];
              r[d] = reference[i][d];
            }
          const double       length = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
          const Vec3<double> r_cross_e = cross(r, e), N_cross_r = cross(N, r);
          const double       n = N[0] * r[0] + N[1] * r[1] + N[2] * r[2];
          const double       c =
            (N[0] * r_cross_e[0] + N[1] * r_cross_e[1] + N[2] * r_cross_e[2]) / length;
          const double h = norm_N / length, denominator = n * n + c * c;
          // Reciprocals once: the loop below would otherwise divide 24 times per edge.
          const double inverse_length      = 1. / length,
                       inverse_denominator = 1. / denominator;
          altitude[i]                      = h;
          tilt[i]                          = std::atan2(c, n);
          const Vec3<double> dn_1 = cross(a2, r), dn_2 = cross(r, a1),
                             dN_1 = cross(a2, r_cross_e), dN_2 = cross(r_cross_e, a1);
          for (unsigned int d = 0; d < 3; ++d)
            for (unsigned int side = 0; side < 2; ++side)
              {
                const double de     = side == 0 ? e_1[i] : e_2[i];
                const double d_norm = side == 0 ? d_norm_1[d] : d_norm_2[d];
                const double d_n    = side == 0 ? dn_1[d] : dn_2[d];
                const double d_N    = side == 0 ? dN_1[d] : dN_2[d];
                const double d_len  = de * e[d] * inverse_length;
                const double d_c = (d_N + de * N_cross_r[d] - c * d_len) * inverse_length;
                const unsigned int j = 3 * side + d;
                d_altitude[i][j]     = (d_norm - h * d_len) * inverse_length;
                d_tilt[i][j]         = (n * d_c - c * d_n) * inverse_denominator;
              }
        }
    }


    std::array<double, 9>
    coordinates(const TrianglePositions &x)
    {
      std::array<double, 9> c;
      for (unsigned int v = 0; v < 3; ++v)
        for (unsigned int d = 0; d < 3; ++d)
          c[3 * v + d] = x[v][d];
      return c;
    }

    // Edge curvatures II_i = 2 h_i f(δ_i).
    std::array<double, 3>
    edge_curvatures(const DirectorFunction   function,
                    const TrianglePositions &x,
                    const EdgeDirectors     &directors,
                    const EdgeAngles        &psi)
    {
      std::array<double, 3> altitude, tilt, curvature;
      edge_geometry(coordinates(x), directors.reference, altitude, tilt);
      for (unsigned int i = 0; i < 3; ++i)
        curvature[i] = 2. * altitude[i] *
                       evaluate(function, tilt[i] + directors.sign[i] * psi[i]).value;
      return curvature;
    }

    // The 2×2 symmetric matrices B_k with b = Σ_k II_k B_k.
    Tensor<2, 2>
    curvature_basis(const unsigned int k)
    {
      Tensor<2, 2> B;
      if (k == 0)
        B[0][0] = B[0][1] = B[1][0] = B[1][1] = 1.;
      else if (k == 1)
        B[0][0] = 1.;
      else
        B[1][1] = 1.;
      return B;
    }
  } // namespace


  BendingRestData
  bending_rest_data(const BendingMaterial   &material,
                    const TrianglePositions &reference,
                    const EdgeDirectors     &rest_directors)
  {
    BendingRestData    rest;
    const Tensor<1, 3> a1 = reference[1] - reference[0], a2 = reference[2] - reference[0];
    const double       area = 0.5 * cross_product_3d(a1, a2).norm();
    Tensor<2, 2>       metric;
    metric[0][0] = a1 * a1;
    metric[0][1] = metric[1][0] = a1 * a2;
    metric[1][1]                = a2 * a2;
    rest.inverse_metric         = invert(metric);

    // C_kl = |T̄| C^abcd (B_k)_ab (B_l)_cd; isotropic: |T̄| D [ν tr(Q B_k) tr(Q B_l) +
    // (1-ν) tr(Q B_k Q B_l)], Q = Ā⁻¹.
    const Tensor<4, 2> C =
      covariant_stiffness(bending_sheet_stiffness(material.rigidity,
                                                  material.poisson_ratio,
                                                  material.weft_rigidity),
                          reference,
                          rest.inverse_metric,
                          material.warp_direction);
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int l = 0; l < 3; ++l)
        rest.stiffness[k][l] =
          area * scalar_product(contract(C, curvature_basis(l)), curvature_basis(k));
    rest.rest_edge_curvature = edge_curvatures(material.director_function,
                                               reference,
                                               rest_directors,
                                               {{0., 0., 0.}});
    return rest;
  }


  std::array<double, 3>
  director_tilts(const TrianglePositions &x,
                 const EdgeDirectors     &directors,
                 const EdgeAngles        &psi)
  {
    std::array<double, 3> altitude, tilt;
    edge_geometry(coordinates(x), directors.reference, altitude, tilt);
    for (unsigned int i = 0; i < 3; ++i)
      tilt[i] = principal_tilt(tilt[i] + directors.sign[i] * psi[i]);
    return tilt;
  }


  double
  barrier_tilt(const DirectorFunction function)
  {
    switch (function)
      {
        case DirectorFunction::tangent:
          return 0.5 * numbers::PI;
        case DirectorFunction::half_tangent:
          return numbers::PI;
        default:
          return 0.;
      }
  }


  double
  tilt_step_bound(const DirectorFunction             function,
                  const TrianglePositions           &x,
                  const std::array<Tensor<1, 3>, 3> &dx,
                  const EdgeDirectors               &directors,
                  const EdgeAngles                  &psi,
                  const EdgeAngles                  &dpsi,
                  double                             alpha)
  {
    const double barrier = barrier_tilt(function);
    if (barrier == 0.)
      return alpha;
    const std::array<double, 3> start    = director_tilts(x, directors, psi);
    const auto                  tilts_at = [&](const double a) {
      TrianglePositions x_a;
      EdgeAngles        psi_a;
      for (unsigned int i = 0; i < 3; ++i)
        {
          x_a[i]   = x[i] + a * dx[i];
          psi_a[i] = psi[i] + a * dpsi[i];
        }
      return director_tilts(x_a, directors, psi_a);
    };
    // Whether `tilts`, followed from `from` (a change of at most π/2), stay on the
    // branch.
    const auto admissible = [&](const std::array<double, 3> &from,
                                const std::array<double, 3> &tilts,
                                std::array<double, 3>       &followed) {
      for (unsigned int i = 0; i < 3; ++i)
        {
          const double change = principal_tilt(tilts[i] - from[i]);
          followed[i]         = from[i] + change;
          if (std::abs(start[i]) >= barrier)
            continue;
          if (std::abs(change) > 0.5 * numbers::PI ||
              std::abs(followed[i]) >
                std::abs(start[i]) + 0.9 * (barrier - std::abs(start[i])))
            return false;
        }
      return true;
    };
    constexpr unsigned int n_samples = 4;
    for (unsigned int halvings = 0; halvings <= 30; ++halvings, alpha *= 0.5)
      {
        std::array<double, 3> from = start, followed;
        bool                  ok   = true;
        for (unsigned int k = 1; k <= n_samples && ok; ++k, from = followed)
          ok = admissible(from, tilts_at(alpha * k / n_samples), followed);
        if (ok)
          return alpha;
      }
    return 0.;
  }


  double
  bending_energy(const BendingMaterial   &material,
                 const BendingRestData   &rest,
                 const TrianglePositions &x,
                 const EdgeDirectors     &directors,
                 const EdgeAngles        &psi)
  {
    const std::array<double, 3> II =
      edge_curvatures(material.director_function, x, directors, psi);
    double energy = 0.;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int l = 0; l < 3; ++l)
        energy += 0.5 * (II[k] - rest.rest_edge_curvature[k]) * rest.stiffness[k][l] *
                  (II[l] - rest.rest_edge_curvature[l]);
    return energy;
  }


  double
  bending_energy_gradient_hessian(const BendingMaterial   &material,
                                  const BendingRestData   &rest,
                                  const TrianglePositions &x,
                                  const EdgeDirectors     &directors,
                                  const EdgeAngles        &psi,
                                  const bool               gauss_newton,
                                  BendingVector           &gradient,
                                  BendingMatrix           *hessian)
  {
    // h_i and φ_i with their first derivatives in the 6 edge-basis coordinates a =
    // (a_1, a_2) (below), and for the exact Hessian their first and second derivatives in
    // the 9 coordinates.
    std::array<double, 3>                h, phi;
    std::array<std::array<double, 6>, 3> d_altitude, d_tilt; // in a = (a_1, a_2)
    std::array<std::array<double, 9>, 3> dh, dphi;           // in x (exact Hessian only)
    // Second derivatives: written (every entry) and read only with the exact Hessian, so
    // not zeroed here (3.9 kB per triangle, on every gradient).
    std::array<std::array<std::array<double, 9>, 9>, 3> ddh, ddphi;
    const auto c_x = [&x](const unsigned int component, const unsigned int vertex) {
      return x[vertex][component];
    };
    const bool exact_hessian = hessian != nullptr && !gauss_newton;
    // h_i and φ_i depend on the positions only through a_1 = x1 - x0 and a_2 = x2 - x0
    // (translation invariance): differentiate in those 6 variables, then map with
    // ∂/∂x1 = ∂/∂a_1, ∂/∂x2 = ∂/∂a_2, ∂/∂x0 = -(∂/∂a_1 + ∂/∂a_2).
    const auto to_vertices = [](const std::array<double, 6> &d6,
                                std::array<double, 9>       &d9) {
      for (unsigned int c = 0; c < 3; ++c)
        {
          d9[3 + c] = d6[c];
          d9[6 + c] = d6[3 + c];
          d9[c]     = -d6[c] - d6[3 + c];
        }
    };
    std::array<double, 6> a;
    for (unsigned int c = 0; c < 3; ++c)
      {
        a[c]     = c_x(c, 1) - c_x(c, 0);
        a[3 + c] = c_x(c, 2) - c_x(c, 0);
      }
    if (exact_hessian)
      {
        using Inner = Sacado::Fad::SFad<double, 6>;
        using Outer = Sacado::Fad::SFad<Inner, 6>;
        std::array<Outer, 9> xs;
        for (unsigned int c = 0; c < 3; ++c)
          {
            xs[c]     = Outer(0.);
            xs[3 + c] = Outer(6, c, Inner(6, c, a[c]));
            xs[6 + c] = Outer(6, 3 + c, Inner(6, 3 + c, a[3 + c]));
          }
        std::array<Outer, 3> altitude, tilt;
        edge_geometry(xs, directors.reference, altitude, tilt);
        std::array<std::array<double, 6>, 6> dd6_h, dd6_phi;
        std::array<std::array<double, 9>, 6> half_h, half_phi; // rows in a, columns in x
        for (unsigned int i = 0; i < 3; ++i)
          {
            h[i]   = altitude[i].val().val();
            phi[i] = tilt[i].val().val();
            for (unsigned int j = 0; j < 6; ++j)
              {
                d_altitude[i][j] = altitude[i].dx(j).val();
                d_tilt[i][j]     = tilt[i].dx(j).val();
                for (unsigned int k = 0; k < 6; ++k)
                  {
                    dd6_h[j][k]   = altitude[i].dx(j).dx(k);
                    dd6_phi[j][k] = tilt[i].dx(j).dx(k);
                  }
                to_vertices(dd6_h[j], half_h[j]);
                to_vertices(dd6_phi[j], half_phi[j]);
              }
            to_vertices(d_altitude[i], dh[i]);
            to_vertices(d_tilt[i], dphi[i]);
            // Second derivatives: the same map on both sides.
            for (unsigned int k = 0; k < 9; ++k)
              {
                std::array<double, 6> column_h, column_phi;
                std::array<double, 9> mapped_h, mapped_phi;
                for (unsigned int j = 0; j < 6; ++j)
                  {
                    column_h[j]   = half_h[j][k];
                    column_phi[j] = half_phi[j][k];
                  }
                to_vertices(column_h, mapped_h);
                to_vertices(column_phi, mapped_phi);
                for (unsigned int j = 0; j < 9; ++j)
                  {
                    ddh[i][j][k]   = mapped_h[j];
                    ddphi[i][j][k] = mapped_phi[j];
                  }
              }
          }
      }
    else
      edge_geometry_gradient(a, directors.reference, h, phi, d_altitude, d_tilt);

    // II_i = 2 h_i f(δ_i) and its gradient in a and in ψ_i.
    std::array<double, 3>                 II, II_minus_rest, dII_psi;
    std::array<DirectorFunctionValues, 3> f;
    std::array<std::array<double, 6>, 3>  dII;
    for (unsigned int i = 0; i < 3; ++i)
      {
        f[i]  = evaluate(material.director_function, phi[i] + directors.sign[i] * psi[i]);
        II[i] = 2. * h[i] * f[i].value;
        II_minus_rest[i] = II[i] - rest.rest_edge_curvature[i];
        for (unsigned int j = 0; j < 6; ++j)
          dII[i][j] =
            2. * (f[i].value * d_altitude[i][j] + h[i] * f[i].first * d_tilt[i][j]);
        dII_psi[i] = 2. * h[i] * f[i].first * directors.sign[i];
      }

    // g = C (II - ĪI): the work-conjugate of each edge curvature.
    std::array<double, 3> g{};
    double                energy = 0.;
    for (unsigned int k = 0; k < 3; ++k)
      {
        for (unsigned int l = 0; l < 3; ++l)
          g[k] += rest.stiffness[k][l] * II_minus_rest[l];
        energy += 0.5 * II_minus_rest[k] * g[k];
      }

    std::array<double, 6> g_a{};
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 6; ++j)
        g_a[j] += g[i] * dII[i][j];
    std::array<double, 9> g_x;
    to_vertices(g_a, g_x);
    for (unsigned int j = 0; j < 9; ++j)
      gradient[j] = g_x[j];
    for (unsigned int i = 0; i < 3; ++i)
      gradient[9 + i] = g[i] * dII_psi[i];

    if (hessian == nullptr)
      return energy;

    // Gauss–Newton part Σ_ik C_ik ∇II_i ∇II_kᵀ, symmetric (C is), in a and ψ, then the
    // positions' block mapped to the vertices (edge_basis_to_vertices). With q_k = Σ_i
    // C_ki ∇_a II_i: H_aa = Σ_k ∇_a II_k q_kᵀ, H_aψ_k = q_k ∂II_k/∂ψ_k, H_ψ_iψ_k = C_ik
    // ∂II_i/∂ψ_i ∂II_k/∂ψ_k.
    BendingMatrix                       &H = *hessian;
    std::array<std::array<double, 6>, 3> q{};
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 6; ++j)
          q[k][j] += rest.stiffness[k][i] * dII[i][j];
    double blocks[3][3][3]; // H_11, H_12, H_22 of H_aa (H_11, H_22 mirrored)
    for (unsigned int b = 0; b < 3; ++b)
      for (unsigned int r = 0; r < 3; ++r)
        for (unsigned int c = b == 1 ? 0 : r; c < 3; ++c)
          {
            const unsigned int row = b == 2 ? 3 + r : r, column = b == 0 ? c : 3 + c;
            blocks[b][r][c] = dII[0][row] * q[0][column] + dII[1][row] * q[1][column] +
                              dII[2][row] * q[2][column];
            if (b != 1)
              blocks[b][c][r] = blocks[b][r][c];
          }
    edge_basis_to_vertices(blocks, H);
    for (unsigned int k = 0; k < 3; ++k)
      {
        std::array<double, 9> q_x;
        to_vertices(q[k], q_x);
        for (unsigned int a = 0; a < 9; ++a)
          H[a][9 + k] = H[9 + k][a] = q_x[a] * dII_psi[k];
        for (unsigned int i = 0; i < 3; ++i)
          H[9 + i][9 + k] = rest.stiffness[i][k] * dII_psi[i] * dII_psi[k];
      }
    if (gauss_newton)
      return energy;

    // Curvature part Σ_i g_i ∇²II_i with
    //   ∇²II_i = 2 [f ∇²h + f' (∇h ∇φᵀ + ∇φ ∇hᵀ) + h f'' ∇φ ∇φᵀ + h f' ∇²φ]  (positions)
    //   ∂²II_i/∂x∂ψ_i = 2 s_i [f' ∇h + h f'' ∇φ],   ∂²II_i/∂ψ_i² = 2 h f''.
    for (unsigned int i = 0; i < 3; ++i)
      {
        const double w  = 2. * g[i];
        const auto  &fi = f[i];
        for (unsigned int a = 0; a < 9; ++a)
          {
            for (unsigned int b = 0; b < 9; ++b)
              H[a][b] += w * (fi.value * ddh[i][a][b] +
                              fi.first * (dh[i][a] * dphi[i][b] + dphi[i][a] * dh[i][b]) +
                              h[i] * fi.second * dphi[i][a] * dphi[i][b] +
                              h[i] * fi.first * ddphi[i][a][b]);
            const double mixed = w * directors.sign[i] *
                                 (fi.first * dh[i][a] + h[i] * fi.second * dphi[i][a]);
            H[a][9 + i] += mixed;
            H[9 + i][a] += mixed;
          }
        H[9 + i][9 + i] += w * h[i] * fi.second;
      }
    return energy;
  }


  double
  curvature_change_norm(const BendingMaterial   &material,
                        const BendingRestData   &rest,
                        const TrianglePositions &x,
                        const EdgeDirectors     &directors,
                        const EdgeAngles        &psi)
  {
    const std::array<double, 3> II =
      edge_curvatures(material.director_function, x, directors, psi);
    Tensor<2, 2> db;
    for (unsigned int k = 0; k < 3; ++k)
      db += (II[k] - rest.rest_edge_curvature[k]) * curvature_basis(k);
    const Tensor<2, 2> M = rest.inverse_metric * db;
    return std::sqrt(std::abs(trace(M * M)));
  }


  Tensor<1, 3>
  edge_director(const Point<3>     &first,
                const Point<3>     &second,
                const Tensor<1, 3> &reference,
                const double        psi)
  {
    const Tensor<1, 3> edge = (second - first) / (second - first).norm();
    const Tensor<1, 3> p    = reference - (reference * edge) * edge;
    const Tensor<1, 3> d = std::cos(psi) * p + std::sin(psi) * cross_product_3d(edge, p);
    return d / p.norm();
  }
} // namespace clothsim::physics
