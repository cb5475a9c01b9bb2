#include "physics/pair_barrier.h"

#include "physics/contact_potential.h"

#include <Sacado.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace clothsim::physics
{
  namespace
  {
    // κ m(x) s(d) on any number type (the mollifier if threshold > 0), d the pair's
    // distance less `offset`; `distance`, if non-null, gets d.
    template <typename Number>
    Number
    potential(const DistanceType                         &type,
              const std::array<std::array<Number, 3>, 4> &X,
              const double                                kappa,
              const double                                d_hat,
              const double                                threshold,
              const double                                offset,
              Number                                     *distance = nullptr)
    {
      using std::log;
      using std::sqrt;
      const Number d = sqrt(squared_distance<Number>(type.form, X, type.points)) - offset;
      if (distance != nullptr)
        *distance = d;
      Number s = -(d - d_hat) * (d - d_hat) * log(d / d_hat);
      if (threshold > 0.)
        {
          const auto   ea = pair_detail::minus(X[1], X[0]);
          const auto   eb = pair_detail::minus(X[3], X[2]);
          const auto   n  = pair_detail::cross(ea, eb);
          const Number x  = pair_detail::dot(n, n);
          if (x < threshold)
            s *= (2. - x / threshold) * x / threshold;
        }
      return kappa * s;
    }

    // The derivatives in the coordinates of the `active` points (N = 3 per point), by
    // nested forward-mode differentiation (`hessian`) or one level (gradient only, and
    // then the distance's gradient in `distance_gradient`).
    template <int N>
    void
    differentiate(const DistanceType        &type,
                  const PairPoints          &x,
                  const std::array<bool, 4> &active,
                  const double               kappa,
                  const double               d_hat,
                  const double               threshold,
                  const double               offset,
                  const bool                 hessian,
                  PairBarrier               &result,
                  std::array<double, 12>    &distance_gradient)
    {
      result.n = N;
      if (hessian)
        {
          using Inner = Sacado::Fad::SFad<double, N>;
          using Outer = Sacado::Fad::SFad<Inner, N>;
          std::array<std::array<Outer, 3>, 4> X;
          unsigned int                        k = 0;
          for (unsigned int i = 0; i < 4; ++i)
            for (unsigned int c = 0; c < 3; ++c)
              if (active[i])
                {
                  X[i][c] = Outer(N, k, Inner(N, k, x[i][c]));
                  ++k;
                }
              else
                X[i][c] = Outer(Inner(x[i][c]));
          const Outer phi = potential(type, X, kappa, d_hat, threshold, offset);
          result.value    = phi.val().val();
          for (unsigned int i = 0; i < N; ++i)
            {
              result.gradient[i] = phi.dx(i).val();
              for (unsigned int j = 0; j < N; ++j)
                result.hessian[i * N + j] = 0.5 * (phi.dx(i).dx(j) + phi.dx(j).dx(i));
            }
          return;
        }
      using Number = Sacado::Fad::SFad<double, N>;
      std::array<std::array<Number, 3>, 4> X;
      unsigned int                         k = 0;
      for (unsigned int i = 0; i < 4; ++i)
        for (unsigned int c = 0; c < 3; ++c)
          X[i][c] = active[i] ? Number(N, k++, x[i][c]) : Number(x[i][c]);
      Number       d;
      const Number phi = potential(type, X, kappa, d_hat, threshold, offset, &d);
      result.value     = phi.val();
      for (unsigned int i = 0; i < N; ++i)
        {
          result.gradient[i]   = phi.dx(i);
          distance_gradient[i] = d.dx(i);
        }
    }
  } // namespace


  PairBarrier
  pair_barrier(const PairKind             kind,
               const PairPoints          &x,
               const std::array<bool, 4> &moving,
               const double               kappa,
               const double               d_hat,
               const double               threshold,
               const unsigned int         order,
               const PairHessian          form,
               const bool                 gauss_newton_mollified,
               const double               offset)
  {
    const bool         hessian = order >= 2;
    const DistanceType type    = distance_type(kind, x);
    PairBarrier        result;
    const double       d = std::sqrt(squared_distance(type, x)) - offset;
    result.distance      = d;
    if (d >= d_hat || d <= 0.)
      {
        result.value = kappa * contact::barrier(d, d_hat);
        return result;
      }
    const bool mollified =
      threshold > 0. &&
      cross_product_3d(x[1] - x[0], x[3] - x[2]).norm_square() < threshold;
    if (!mollified && (order == 1 || (hessian && form == PairHessian::gauss_newton)))
      {
        // In closed form: ∇d = (w_i r/|r|)_i with r = Σ w_i x_i between the closest
        // points (closest_point_weights; the weights are optimal, so they do not move
        // d to first order), ∇φ = κ s'(d) ∇d, Gauss-Newton's κ s''(d) ∇d ∇dᵀ.
        const std::array<double, 4> w = closest_point_weights(type, x);
        Tensor<1, 3>                r;
        for (unsigned int i = 0; i < 4; ++i)
          r += w[i] * x[i];
        const Tensor<1, 3>     normal = r / r.norm();
        std::array<double, 12> gradient_d;
        unsigned int           n = 0;
        for (unsigned int i = 0; i < 4; ++i)
          if (moving[i])
            for (unsigned int c = 0; c < 3; ++c)
              gradient_d[n++] = w[i] * normal[c];
        result.n           = n;
        result.value       = kappa * contact::barrier(d, d_hat);
        const double first = kappa * contact::barrier_first(d, d_hat);
        for (unsigned int k = 0; k < n; ++k)
          result.gradient[k] = first * gradient_d[k];
        if (hessian)
          {
            const double second = kappa * contact::barrier_second(d, d_hat);
            for (unsigned int k = 0; k < n; ++k)
              for (unsigned int l = 0; l < n; ++l)
                result.hessian[k * n + l] = second * gradient_d[k] * gradient_d[l];
          }
        return result;
      }
    if (order == 0)
      {
        std::array<std::array<double, 3>, 4> X;
        for (unsigned int i = 0; i < 4; ++i)
          for (unsigned int c = 0; c < 3; ++c)
            X[i][c] = x[i][c];
        result.value = potential(type, X, kappa, d_hat, threshold, offset);
        return result;
      }
    // Only the points of the distance's form (all four while the mollifier acts) have
    // derivatives; the rest of the moving points' entries are zero.
    std::array<bool, 4> active{};
    const unsigned int  n_form = type.form == DistanceType::point_point  ? 2
                                 : type.form == DistanceType::point_line ? 3
                                                                         : 4;
    for (unsigned int k = 0; k < n_form; ++k)
      active[type.points[k]] = true;
    if (mollified)
      active = {{true, true, true, true}};
    unsigned int n_active = 0;
    for (unsigned int i = 0; i < 4; ++i)
      {
        active[i] = active[i] && moving[i];
        n_active += active[i] ? 1 : 0;
      }
    // Gauss-Newton's κ m(x) s''(d) ∇d ∇dᵀ (as for the analytic obstacles, the part
    // κ m s'(d) ∇²d is dropped, and so are the mollifier's derivatives, if it acts), from
    // first derivatives alone; else the exact Hessian by nested differentiation,
    // projected unless `form` is exact.
    const bool project      = form != PairHessian::exact;
    const bool gauss_newton = hessian && form == PairHessian::gauss_newton &&
                              (!mollified || gauss_newton_mollified);
    const bool             nested = hessian && !gauss_newton;
    PairBarrier            reduced;
    std::array<double, 12> distance_gradient{};
    // differentiate<N> for the N = 3 n_active coordinates of the active points.
    const auto differentiate_active = [&](auto points) {
      differentiate<3 * decltype(points)::value>(type,
                                                 x,
                                                 active,
                                                 kappa,
                                                 d_hat,
                                                 threshold,
                                                 offset,
                                                 nested,
                                                 reduced,
                                                 distance_gradient);
    };
    switch (n_active)
      {
        case 1:
          differentiate_active(std::integral_constant<int, 1>());
          break;
        case 2:
          differentiate_active(std::integral_constant<int, 2>());
          break;
        case 3:
          differentiate_active(std::integral_constant<int, 3>());
          break;
        case 4:
          differentiate_active(std::integral_constant<int, 4>());
          break;
          default: {
            std::array<std::array<double, 3>, 4> X;
            for (unsigned int i = 0; i < 4; ++i)
              for (unsigned int c = 0; c < 3; ++c)
                X[i][c] = x[i][c];
            reduced.value = potential(type, X, kappa, d_hat, threshold, offset);
          }
      }
    if (gauss_newton && n_active > 0 && !mollified)
      {
        // ∇φ = κ s'(d) ∇d, so ∇d = ∇φ / (κ s'(d)).
        const double first = kappa * contact::barrier_first(d, d_hat);
        const double curve = kappa * contact::barrier_second(d, d_hat) / (first * first);
        for (unsigned int i = 0; i < reduced.n; ++i)
          for (unsigned int j = 0; j < reduced.n; ++j)
            reduced.hessian[i * reduced.n + j] =
              curve * reduced.gradient[i] * reduced.gradient[j];
      }
    else if (gauss_newton && n_active > 0)
      {
        // ∇φ has the mollifier's gradient in it too: ∇d from its own derivatives.
        const double weight =
          kappa * contact::barrier_second(d, d_hat) *
          mollifier(cross_product_3d(x[1] - x[0], x[3] - x[2]).norm_square(), threshold);
        for (unsigned int i = 0; i < reduced.n; ++i)
          for (unsigned int j = 0; j < reduced.n; ++j)
            reduced.hessian[i * reduced.n + j] =
              weight * distance_gradient[i] * distance_gradient[j];
      }
    else if (hessian && n_active > 0 && project)
      project_to_positive_semidefinite(reduced.hessian.data(), reduced.n);

    // Scatter into the moving points' layout.
    result.value = reduced.value;
    std::array<unsigned int, 4> slot{};
    unsigned int                n = 0, m = 0;
    for (unsigned int i = 0; i < 4; ++i)
      if (moving[i])
        {
          if (active[i])
            slot[m++] = n;
          n += 3;
        }
    result.n = n;
    if (hessian)
      std::fill(result.hessian.begin(), result.hessian.begin() + n * n, 0.);
    for (unsigned int a = 0; a < m; ++a)
      for (unsigned int c = 0; c < 3; ++c)
        {
          result.gradient[slot[a] + c] = reduced.gradient[3 * a + c];
          if (hessian)
            for (unsigned int b = 0; b < m; ++b)
              for (unsigned int e = 0; e < 3; ++e)
                result.hessian[(slot[a] + c) * n + slot[b] + e] =
                  reduced.hessian[(3 * a + c) * reduced.n + 3 * b + e];
        }
    return result;
  }


  void
  project_to_positive_semidefinite(double *A, const unsigned int n)
  {
    // A = V Λ Vᵀ by cyclic Jacobi rotations (A ← Jᵀ A J zeroes A_pq), then
    // A = V max(Λ, 0) Vᵀ.
    std::array<double, 144> V{};
    for (unsigned int i = 0; i < n; ++i)
      V[i * n + i] = 1.;
    double scale = 0.;
    for (unsigned int i = 0; i < n * n; ++i)
      scale += A[i] * A[i];
    for (unsigned int sweep = 0; sweep < 50; ++sweep)
      {
        double off = 0.;
        for (unsigned int p = 0; p < n; ++p)
          for (unsigned int q = p + 1; q < n; ++q)
            off += A[p * n + q] * A[p * n + q];
        if (off <= 1e-30 * scale)
          break;
        for (unsigned int p = 0; p < n; ++p)
          for (unsigned int q = p + 1; q < n; ++q)
            {
              const double apq = A[p * n + q];
              if (apq == 0.)
                continue;
              const double theta = (A[q * n + q] - A[p * n + p]) / (2. * apq);
              const double t     = (theta >= 0. ? 1. : -1.) /
                               (std::abs(theta) + std::sqrt(theta * theta + 1.));
              const double c = 1. / std::sqrt(t * t + 1.), s = t * c;
              for (unsigned int k = 0; k < n; ++k)
                {
                  const double akp = A[k * n + p], akq = A[k * n + q];
                  A[k * n + p] = c * akp - s * akq;
                  A[k * n + q] = s * akp + c * akq;
                }
              for (unsigned int k = 0; k < n; ++k)
                {
                  const double apk = A[p * n + k], aqk = A[q * n + k];
                  A[p * n + k] = c * apk - s * aqk;
                  A[q * n + k] = s * apk + c * aqk;
                }
              for (unsigned int k = 0; k < n; ++k)
                {
                  const double vkp = V[k * n + p], vkq = V[k * n + q];
                  V[k * n + p] = c * vkp - s * vkq;
                  V[k * n + q] = s * vkp + c * vkq;
                }
            }
      }
    std::array<double, 12> lambda{};
    for (unsigned int i = 0; i < n; ++i)
      lambda[i] = std::max(A[i * n + i], 0.);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        {
          double sum = 0.;
          for (unsigned int k = 0; k < n; ++k)
            sum += V[i * n + k] * lambda[k] * V[j * n + k];
          A[i * n + j] = sum;
        }
  }
} // namespace clothsim::physics
