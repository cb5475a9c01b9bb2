#include "physics/friction_term.h"

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include "mesh/ghosted_values.h"
#include "physics/contact_potential.h"

namespace clothsim::physics
{
  ObstacleFriction::ObstacleFriction(const ObstacleContact &contact)
    : GlobalTerm("friction", TermKind::dissipative)
    , contact(contact)
  {}


  double
  ObstacleFriction::add_to_step(const VectorType &u,
                                const StepTerms &,
                                const AffineConstraints<double> &constraints,
                                VectorType                      *gradient,
                                MatrixType                      *hessian,
                                RankVector *dissipative_gradient) const
  {
    const auto   &vertices = contact.vertices();
    const double *local =
      ghosted_values(u, static_cast<unsigned int>(u.trilinos_vector().MyLength()));
    const double epsilon =
      contact.get_settings().slip_velocity * contact.step_length(); // m
    double                               value = 0.;
    Vector<double>                       g(3);
    FullMatrix<double>                   H(3, 3);
    std::vector<types::global_dof_index> dofs(3);
    for (const LaggedContact &lagged : contact.lagged_contacts())
      {
        const auto        &vertex  = vertices[lagged.vertex];
        const Tensor<1, 3> r       = contact.position(vertex, local) - lagged.carried;
        const double       slip[2] = {lagged.tangent[0] * r, lagged.tangent[1] * r};
        const double       y       = std::sqrt(slip[0] * slip[0] + slip[1] * slip[1]);
        value += lagged.mu_lambda * contact::friction_f0(y, epsilon);
        if (gradient == nullptr && hessian == nullptr && dissipative_gradient == nullptr)
          continue;
        // ∇D = μλ f1(y)/y T u_T;  ∇²D = μλ T (f1' ûûᵀ + f1/y (I - ûûᵀ)) Tᵀ.
        const double f1_y  = contact::friction_f1_over_y(y, epsilon);
        const double f1_p  = contact::friction_f1_prime(y, epsilon);
        Tensor<1, 3> along = slip[0] * lagged.tangent[0] + slip[1] * lagged.tangent[1];
        const Tensor<1, 3> force = lagged.mu_lambda * f1_y * along;
        if (y > 0.)
          along /= y;
        const Tensor<2, 3> plane = outer_product(lagged.tangent[0], lagged.tangent[0]) +
                                   outer_product(lagged.tangent[1], lagged.tangent[1]);
        const Tensor<2, 3> along_along = outer_product(along, along);
        const Tensor<2, 3> hess =
          lagged.mu_lambda * (f1_p * along_along + f1_y * (plane - along_along));
        for (unsigned int i = 0; i < 3; ++i)
          {
            dofs[i] = vertex.dofs[i];
            g[i]    = force[i];
            for (unsigned int j = 0; j < 3; ++j)
              H(i, j) = hess[i][j];
            if (dissipative_gradient != nullptr)
              (*dissipative_gradient)[vertex.local[i]] += force[i];
          }
        if (gradient != nullptr)
          constraints.distribute_local_to_global(g, dofs, *gradient);
        if (hessian != nullptr)
          constraints.distribute_local_to_global(H, dofs, *hessian);
      }
    return value;
  }
} // namespace clothsim::physics
