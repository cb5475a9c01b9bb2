#include "physics/friction_term.h"

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include "physics/contact_potential.h"

namespace clothsim::physics
{
  ContactFriction::ContactFriction(const LaggedContacts &contact, const std::string &name)
    : GlobalTerm(name, TermKind::dissipative)
    , contact(contact)
  {}


  double
  ContactFriction::add_to_step(const VectorType &u,
                               const StepTerms &,
                               const AffineConstraints<double> &constraints,
                               VectorType                      *gradient,
                               MatrixType                      *hessian,
                               RankVector *dissipative_gradient) const
  {
    const double                        *local   = contact.point_values(u);
    const double                         epsilon = contact.static_slip(); // m
    double                               value   = 0.;
    Vector<double>                       g;
    FullMatrix<double>                   H;
    std::vector<types::global_dof_index> dofs;
    const std::vector<LaggedContact>    &contacts = contact.lagged_contacts();
    if (hessian != nullptr)
      {
        if (scattered_lags != contact.lag_count())
          for (mesh::ElementMatrixScatter &scatter : scatters)
            scatter.forget();
        scattered_lags = contact.lag_count();
        for (unsigned int k = 0; k < scatters.size(); ++k)
          scatters[k].start(*hessian, contacts.size(), 3 * (k + 1));
      }
    for (unsigned int index = 0; index < contacts.size(); ++index)
      {
        const LaggedContact &lagged = contacts[index];
        // r = Σ w_i (x_i - c_i), the slip u_T = Tᵀ r.
        Tensor<1, 3> r;
        for (unsigned int i = 0; i < lagged.n_points; ++i)
          {
            const FrictionPoint &point = lagged.points[i];
            Tensor<1, 3>         x     = point.reference - point.carried;
            for (unsigned int c = 0; c < 3; ++c)
              x[c] += local[point.local[c]];
            r += point.weight * x;
          }
        const double slip[2] = {lagged.tangent[0] * r, lagged.tangent[1] * r};
        const double y       = std::sqrt(slip[0] * slip[0] + slip[1] * slip[1]);
        if (lagged.counted)
          value += lagged.mu_lambda * contact::friction_f0(y, epsilon);
        if (gradient == nullptr && hessian == nullptr && dissipative_gradient == nullptr)
          continue;
        // ∇_r D = μλ f1(y)/y T u_T;  ∇²_r D = μλ T (f1' ûûᵀ + f1/y (I - ûûᵀ)) Tᵀ;
        // the point i's blocks are w_i (and w_i w_j) times them.
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
        const unsigned int n = 3 * lagged.n_points;
        g.reinit(n);
        H.reinit(n, n);
        dofs.resize(n);
        for (unsigned int a = 0; a < lagged.n_points; ++a)
          for (unsigned int i = 0; i < 3; ++i)
            {
              const FrictionPoint &point = lagged.points[a];
              dofs[3 * a + i]            = point.dofs[i];
              g[3 * a + i]               = point.weight * force[i];
              for (unsigned int b = 0; b < lagged.n_points; ++b)
                for (unsigned int j = 0; j < 3; ++j)
                  H(3 * a + i, 3 * b + j) =
                    point.weight * lagged.points[b].weight * hess[i][j];
              if (dissipative_gradient != nullptr && point.owned)
                (*dissipative_gradient)[point.relevant[i]] += point.weight * force[i];
            }
        // Each owned point's own block; then the gradient and the whole tangent, or for
        // a contact across ranks their rows of this rank's points.
        if (hessian != nullptr && lagged.diagonal_only)
          for (unsigned int a = 0; a < lagged.n_points; ++a)
            if (lagged.points[a].owned)
              {
                FullMatrix<double>                   block(3, 3);
                std::vector<types::global_dof_index> point_dofs(3);
                for (unsigned int r = 0; r < 3; ++r)
                  {
                    point_dofs[r] = dofs[3 * a + r];
                    for (unsigned int c = 0; c < 3; ++c)
                      block(r, c) = H(3 * a + r, 3 * a + c);
                  }
                constraints.distribute_local_to_global(block, point_dofs, *hessian);
              }
        MatrixType *full      = lagged.diagonal_only ? nullptr : hessian;
        bool        all_owned = true;
        for (unsigned int a = 0; a < lagged.n_points; ++a)
          all_owned = all_owned && lagged.points[a].owned;
        if (!all_owned)
          add_owned_rows(lagged, g, H, dofs, constraints, gradient, full);
        else
          {
            if (gradient != nullptr)
              constraints.distribute_local_to_global(g, dofs, *gradient);
            if (full != nullptr &&
                !scatters[lagged.n_points - 1].add(index, dofs, H, constraints))
              constraints.distribute_local_to_global(H, dofs, *full);
          }
      }
    return value;
  }


  void
  ContactFriction::add_owned_rows(const LaggedContact                        &lagged,
                                  const Vector<double>                       &g,
                                  const FullMatrix<double>                   &H,
                                  const std::vector<types::global_dof_index> &dofs,
                                  const AffineConstraints<double>            &constraints,
                                  VectorType                                 *gradient,
                                  MatrixType                                 *hessian)
  {
    // The rows of the points this rank owns (their owners add the others'), with all
    // columns.
    std::vector<unsigned int> rows;
    for (unsigned int a = 0; a < lagged.n_points; ++a)
      if (lagged.points[a].owned)
        for (unsigned int i = 0; i < 3; ++i)
          rows.push_back(3 * a + i);
    if (rows.empty())
      return;
    std::vector<types::global_dof_index> row_dofs;
    Vector<double>                       g_rows(rows.size());
    for (unsigned int k = 0; k < rows.size(); ++k)
      {
        row_dofs.push_back(dofs[rows[k]]);
        g_rows[k] = g[rows[k]];
      }
    if (gradient != nullptr)
      constraints.distribute_local_to_global(g_rows, row_dofs, *gradient);
    if (hessian == nullptr)
      return;
    FullMatrix<double> H_rows(rows.size(), dofs.size());
    for (unsigned int k = 0; k < rows.size(); ++k)
      for (unsigned int j = 0; j < dofs.size(); ++j)
        H_rows(k, j) = H(rows[k], j);
    constraints.distribute_local_to_global(H_rows, row_dofs, dofs, *hessian);
  }
} // namespace clothsim::physics
