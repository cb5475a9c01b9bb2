#include "time/step_problem.h"

#include "io/collective.h"

#include <cmath>
#include <cstring>

namespace clothsim
{
  namespace
  {
    // Two-point Gauss quadrature on [0, 1]: weight 1/2 at s = 1/2 ∓ √3/6; the path's
    // point is q_n + c (x - q_n) with c = 2s.
    constexpr double gauss_weight = 0.5;
    const double     gauss_c[2]   = {1. - 1. / std::sqrt(3.), 1. + 1. / std::sqrt(3.)};

    // Whether a and b (same layout) hold the same bits on every rank (collective).
    bool
    bitwise_equal(const VectorType &a, const VectorType &b, const MPI_Comm communicator)
    {
      const auto n = a.locally_owned_size();
      return io::on_all_ranks(n == b.locally_owned_size() &&
                                std::memcmp(a.begin(),
                                            b.begin(),
                                            n * sizeof(*a.begin())) == 0,
                              communicator);
    }
  } // namespace


  StepProblem::StepProblem(ModelInterface  &model,
                           const StepTerms &terms,
                           TimerOutput     &timer)
    : model(model)
    , terms(terms)
    , timer(timer)
  {
    model.initialize_ghosted(ghosted);
    model.initialize_ghosted(ghosted_direction);
  }


  void
  StepProblem::average_along_path_from(const VectorType &start, MatrixType &scratch)
  {
    path_start    = &start;
    first_tangent = &scratch;
    model.initialize_owned(owned_point);
    model.initialize_owned(owned_sum);
  }


  void
  StepProblem::linearise_stress_from(const VectorType &start)
  {
    tangent_points.assign(path_start == nullptr ? 1 : 2, start);
    earlier_tangent_points = tangent_points;
    model.initialize_ghosted(linearised_from);
    model.initialize_owned(scratch);
  }


  void
  StepProblem::assemble_tangent(const unsigned int node,
                                const VectorType  &x,
                                MatrixType        &J)
  {
    if (tangent_points.empty())
      {
        model.assemble(ghosted, terms, nullptr, &J);
        return;
      }
    // A second tangent at the same point (the adaptive tangent's projected retry)
    // linearises from the same point as the first.
    if (new_tangent_point(node, x))
      {
        earlier_tangent_points[node] = tangent_points[node];
        tangent_points[node]         = x;
      }
    model.import_ghosts(earlier_tangent_points[node], linearised_from);
    terms.linearised_from = &linearised_from;
    model.assemble(ghosted, terms, nullptr, &J);
    terms.linearised_from = nullptr;
  }


  bool
  StepProblem::new_tangent_point(const unsigned int node, const VectorType &x)
  {
    scratch = x;
    scratch -= tangent_points[node];
    return scratch.linfty_norm() != 0.;
  }


  void
  StepProblem::speculate_tangents(MatrixType *J, const bool projected)
  {
    speculative_matrix = path_start == nullptr ? J : static_cast<MatrixType *>(nullptr);
    speculative_projected   = projected;
    tangent_at_cached_point = false;
  }


  double
  StepProblem::assemble_at(const VectorType &u, VectorType &gradient)
  {
    model.import_ghosts(u, ghosted);
    cached_point            = u;
    cached                  = true;
    tangent_at_cached_point = false;
    if (speculative_matrix == nullptr)
      return model.assemble(ghosted, terms, &gradient, nullptr);
    // The tangent as tangent() would assemble it at u; the tangent points move only
    // when it is asked for.
    terms.projected_tangent = speculative_projected;
    if (!tangent_points.empty())
      {
        model.import_ghosts(new_tangent_point(0, u) ? tangent_points[0]
                                                    : earlier_tangent_points[0],
                            linearised_from);
        terms.linearised_from = &linearised_from;
      }
    const double energy   = model.assemble(ghosted, terms, &gradient, speculative_matrix);
    terms.linearised_from = nullptr;
    tangent_at_cached_point = true;
    return energy;
  }


  void
  StepProblem::set_path_point(const VectorType &x, const double c)
  {
    owned_point = x;
    owned_point.sadd(c, 1. - c, *path_start);
    model.import_ghosts(owned_point, ghosted);
  }


  double
  StepProblem::largest_step(const VectorType &u, const VectorType &direction)
  {
    if (!model.caps_steps())
      return 1.;
    TimerOutput::Scope scope(timer, "line search: step cap");
    if (path_start == nullptr)
      {
        model.import_ghosts(u, ghosted);
        model.import_ghosts(direction, ghosted_direction);
        return model.largest_step(ghosted, ghosted_direction, terms.time);
      }
    // The averaged potential reads the path's points q_n + c (x - q_n), which move by
    // c times the update: each must stay admissible, and so must the step's end (c = 2).
    double alpha = 1.;
    for (const double c : {gauss_c[0], gauss_c[1], 2.})
      {
        set_path_point(u, c);
        owned_sum = direction; // scratch
        owned_sum *= c;
        model.import_ghosts(owned_sum, ghosted_direction);
        alpha =
          std::min(alpha, model.largest_step(ghosted, ghosted_direction, terms.time));
      }
    return alpha;
  }


  bool
  StepProblem::adapt(const VectorType &u)
  {
    // The contact terms judge the point they were last assembled at.
    if (!at_cached_point(u))
      objective(u);
    if (!model.adapt_to_iterate())
      return false;
    forget_cached_values();
    return true;
  }


  double
  StepProblem::objective(const VectorType &u)
  {
    TimerOutput::Scope scope(timer, "assemble energy");
    if (path_start == nullptr)
      {
        if (!at_cached_point(u))
          {
            if (cached_gradient.size() == 0)
              model.initialize_owned(cached_gradient);
            cached_energy = assemble_at(u, cached_gradient);
          }
        return cached_energy;
      }
    // G(x) + Φ(q_n) Σ w/c: the constant does not change the minimiser.
    double value = 0.;
    for (const double c : gauss_c)
      {
        set_path_point(u, c);
        value += gauss_weight / c * model.assemble(ghosted, terms, nullptr, nullptr);
      }
    return value;
  }


  bool
  StepProblem::at_cached_point(const VectorType &u) const
  {
    return cached && bitwise_equal(u, cached_point, model.get_communicator());
  }


  void
  StepProblem::residual(const VectorType &u, VectorType &F)
  {
    TimerOutput::Scope scope(timer, "assemble residual");
    if (path_start == nullptr)
      {
        if (!at_cached_point(u))
          {
            cached_energy   = assemble_at(u, F);
            cached_gradient = F;
            return;
          }
        F = cached_gradient;
        return;
      }
    // ḡ = Σ w ∇Φ(q_n + c (x - q_n))
    set_path_point(u, gauss_c[0]);
    model.assemble(ghosted, terms, &owned_sum, nullptr);
    set_path_point(u, gauss_c[1]);
    model.assemble(ghosted, terms, &F, nullptr);
    F.sadd(gauss_weight, gauss_weight, owned_sum);
  }


  void
  StepProblem::tangent(const VectorType &u, MatrixType &J, const bool projected)
  {
    TimerOutput::Scope scope(timer, "assemble tangent");
    terms.projected_tangent = projected;
    if (path_start == nullptr)
      {
        if (tangent_at_cached_point && &J == speculative_matrix &&
            projected == speculative_projected && at_cached_point(u))
          {
            // Assembled with Φ at u (speculate_tangents): the tangent points move as
            // assemble_tangent would have moved them.
            if (!tangent_points.empty() && new_tangent_point(0, u))
              {
                earlier_tangent_points[0] = tangent_points[0];
                tangent_points[0]         = u;
              }
            tangent_at_cached_point = false;
            return;
          }
        tangent_at_cached_point = false; // J is overwritten
        model.import_ghosts(u, ghosted);
        assemble_tangent(0, u, J);
        return;
      }
    // Σ w c ∇²Φ(q_n + c (x - q_n)); each node's projected Hessian is positive
    // semi-definite, so is their sum. The unit diagonal of constrained rows stays one:
    // Σ w c = 1. Both nodes are assembled into J (its assembly keeps the positions it
    // found in J's value arrays); the first is parked in a copy of the same sparsity
    // (a deep copy only the first time).
    set_path_point(u, gauss_c[0]);
    assemble_tangent(0, owned_point, J);
    first_tangent->copy_from(J);
    set_path_point(u, gauss_c[1]);
    assemble_tangent(1, owned_point, J);
    J *= gauss_weight * gauss_c[1];
    J.add(gauss_weight * gauss_c[0], *first_tangent);
  }


  double
  StepProblem::update_size(const VectorType &update) const
  {
    double largest = 0.;
    for (const types::global_dof_index i : model.displacement_dofs())
      largest = std::max(largest, std::abs(update[i]));
    return Utilities::MPI::max(largest, model.get_communicator());
  }
} // namespace clothsim
