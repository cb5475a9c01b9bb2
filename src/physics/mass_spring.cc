#include "physics/mass_spring.h"

#include <cmath>

namespace clothsim::physics
{
  double
  spring_energy(const Spring &spring, const SpringPositions &x)
  {
    const double stretch = (x[1] - x[0]).norm() - spring.rest_length;
    return 0.5 * spring.stiffness * stretch * stretch;
  }

  double
  spring_energy_gradient_hessian(const Spring          &spring,
                                 const SpringPositions &x,
                                 const bool             project,
                                 SpringVector          &gradient,
                                 SpringMatrix          *hessian)
  {
    const Tensor<1, 3> d       = x[1] - x[0];
    const double       length  = d.norm();
    const double       k       = spring.stiffness;
    const double       stretch = length - spring.rest_length;
    const double       energy  = 0.5 * k * stretch * stretch;

    gradient.fill(0.);
    if (hessian != nullptr)
      for (auto &row : *hessian)
        row.fill(0.);
    if (length == 0.)
      return energy;

    const Tensor<1, 3> u = d / length;
    for (unsigned int i = 0; i < 3; ++i)
      {
        gradient[i]     = -k * stretch * u[i];
        gradient[3 + i] = k * stretch * u[i];
      }
    if (hessian == nullptr)
      return energy;

    // K = k [u ⊗ u + t (I - u ⊗ u)], t = 1 - L/ℓ (dropped under compression if
    // projecting).
    double transverse = 1. - spring.rest_length / length;
    if (project && transverse < 0.)
      transverse = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          const double K =
            k * ((1. - transverse) * u[i] * u[j] + (i == j ? transverse : 0.));
          (*hessian)[i][j]         = K;
          (*hessian)[3 + i][3 + j] = K;
          (*hessian)[i][3 + j]     = -K;
          (*hessian)[3 + i][j]     = -K;
        }
    return energy;
  }

  double
  structural_spring_stiffness(const double stretch_stiffness,
                              const double poisson_ratio,
                              const double rest_length,
                              const double area_1,
                              const double area_2)
  {
    const double nu     = poisson_ratio;
    const double factor = 8. / (9. * (1. - nu * nu)); // c(ν), 1 at ν = 1/3
    return factor * stretch_stiffness * (area_1 + area_2) / (rest_length * rest_length);
  }

  double
  hinge_bending_coefficient(const double rigidity,
                            const double edge_length,
                            const double area_1,
                            const double area_2)
  {
    return rigidity * edge_length * edge_length / (2. * (area_1 + area_2));
  }

  double
  bend_spring_stiffness(const double rigidity,
                        const double edge_length,
                        const double area_1,
                        const double area_2,
                        const double bend_rest_length,
                        const double reference_angle)
  {
    const double c  = hinge_bending_coefficient(rigidity, edge_length, area_1, area_2);
    const double h1 = 2. * area_1 / edge_length, h2 = 2. * area_2 / edge_length;
    // ℓ² = L_b² - 2 h1 h2 (1 - cos θ); 1 - cos θ = 2 sin²(θ/2) without cancellation.
    const double s             = std::sin(0.5 * reference_angle);
    const double one_minus_cos = 2. * s * s;
    const double folded_length =
      std::sqrt(bend_rest_length * bend_rest_length - 2. * h1 * h2 * one_minus_cos);
    const double shortening =
      2. * h1 * h2 * one_minus_cos / (bend_rest_length + folded_length);
    return 2. * c * reference_angle * reference_angle / (shortening * shortening);
  }

  SpringPositions
  limit_strain(const SpringPositions &x,
               const double           rest_length,
               const double           limit,
               const double           inverse_mass_0,
               const double           inverse_mass_1,
               const bool             limit_compression)
  {
    const Tensor<1, 3> d            = x[1] - x[0];
    const double       length       = d.norm();
    const double       total_weight = inverse_mass_0 + inverse_mass_1;
    if (length == 0. || total_weight == 0.)
      return x;

    double target = length;
    if (length > (1. + limit) * rest_length)
      target = (1. + limit) * rest_length;
    else if (limit_compression && length < (1. - limit) * rest_length)
      target = (1. - limit) * rest_length;
    else
      return x;

    // Move x0 towards x1 by w0/(w0+w1) of the excess and x1 towards x0 by the rest.
    const Tensor<1, 3> excess = (length - target) / length * d;
    SpringPositions    y      = x;
    y[0] += (inverse_mass_0 / total_weight) * excess;
    y[1] -= (inverse_mass_1 / total_weight) * excess;
    return y;
  }
} // namespace clothsim::physics
