#include "physics/model.h"

#include "mesh/ghosted_values.h"
#include "physics/wall_clock.h"

#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace clothsim::physics
{
  namespace
  {
    using Clock = WallClock;

    // Every how many triangles the element terms are timed.
    constexpr unsigned int timing_stride = 64;

    // The cost of timing nothing (two clock reads), s, subtracted from each sample.
    double
    clock_overhead()
    {
      constexpr unsigned int n     = 1000;
      double                 total = 0.;
      for (unsigned int i = 0; i < n; ++i)
        total += seconds_since(Clock::now());
      return total / n;
    }
  } // namespace


  std::string
  Term::report_column() const
  {
    std::string column = name() + "_energy";
    std::replace(column.begin(), column.end(), ' ', '_');
    return column;
  }


  Model::Model(const mesh::Discretization      &discretization,
               const AffineConstraints<double> &constraints)
    : discretization(discretization)
    , constraints(constraints)
    , directors(discretization.has_directors())
    , n_relevant_dofs(discretization.relevant_dofs().n_elements())
    , timing_overhead(clock_overhead())
  {
    for (const auto &element : discretization.elements())
      rest.push_back(membrane_rest_data(element.reference));
    for (const types::global_dof_index dof : discretization.unused_dofs())
      if (discretization.owned_dofs().is_element(dof))
        owned_unused_dofs.push_back(dof);
  }


  void
  Model::add(std::unique_ptr<ElementTerm> term)
  {
    AssertThrow(global_terms.empty(),
                ExcMessage("element terms come before the other terms"));
    all_terms.push_back(term.get());
    assemblers.push_back(term.get());
    seconds.push_back(0.);
    element_terms.push_back(std::move(term));
  }


  void
  Model::add(std::unique_ptr<GlobalTerm> term)
  {
    // Left to its host if the host is in the model already.
    const Term *host = term->host();
    if (host == nullptr ||
        std::find(all_terms.begin(), all_terms.end(), host) == all_terms.end())
      host = term.get();
    all_terms.push_back(term.get());
    assemblers.push_back(host);
    seconds.push_back(0.);
    global_terms.push_back(std::move(term));
  }


  const Term *
  Model::assembled_by(const unsigned int k) const
  {
    AssertIndexRange(k, assemblers.size());
    return assemblers[k];
  }


  const Term *
  Model::find(const std::string &name) const
  {
    for (const Term *term : all_terms)
      if (term->name() == name)
        return term;
    return nullptr;
  }


  bool
  Model::has_dissipation() const
  {
    return std::any_of(all_terms.begin(), all_terms.end(), [](const Term *term) {
      return term->kind() == TermKind::dissipative;
    });
  }


  void
  Model::initialize_matrix(MatrixType &matrix) const
  {
    discretization.initialize_matrix(matrix,
                                     constraints,
                                     [this](TrilinosWrappers::SparsityPattern &sparsity) {
                                       for (const auto &term : global_terms)
                                         term->add_couplings(sparsity, constraints);
                                     });
  }


  template <class Function>
  void
  Model::for_each_element(const VectorType &u,
                          const VectorType *predictor,
                          const VectorType *previous,
                          const Function   &function,
                          const VectorType *linearised_from) const
  {
    std::array<double, 9> u_e, predictor_e, previous_e, from_e;
    TrianglePositions     from_x;
    EdgeAngles            psi      = {{0., 0., 0.}};
    const auto           &elements = discretization.elements();
    for (unsigned int e = 0; e < elements.size(); ++e)
      {
        const auto             &element = elements[e];
        const TrianglePositions x = discretization.current_positions(element, u, u_e);
        if (predictor != nullptr)
          discretization.gather(*predictor, element, predictor_e);
        else
          predictor_e = u_e;
        if (previous != nullptr)
          discretization.gather(*previous, element, previous_e);
        else
          previous_e = u_e;
        if (directors)
          psi = discretization.angles(u, element);
        if (linearised_from != nullptr)
          from_x = discretization.current_positions(element, *linearised_from, from_e);
        function(ElementState{e,
                              element.reference,
                              rest[e],
                              x,
                              u_e,
                              predictor_e,
                              previous_e,
                              psi,
                              linearised_from != nullptr ? &from_x : nullptr});
      }
  }


  double
  Model::assemble(const VectorType &u,
                  const StepTerms  &step,
                  VectorType       *gradient,
                  MatrixType       *hessian,
                  RankVector       *dissipative_gradient) const
  {
    const VectorType *predictor = step.inertia_weight > 0. ? step.predictor : nullptr;
    const VectorType *previous =
      step.damping_weight > 0. && has_dissipation() ? step.previous : nullptr;
    Assert(step.inertia_weight == 0. || predictor != nullptr, ExcInternalError());
    Assert(step.damping_weight == 0. || !has_dissipation() || previous != nullptr,
           ExcInternalError());
    if (gradient != nullptr)
      *gradient = 0.;
    if (hessian != nullptr)
      *hessian = 0.;
    if (dissipative_gradient != nullptr)
      dissipative_gradient->assign(n_relevant_dofs, 0.);
    if (gradient != nullptr)
      gradient_sums.start(u);
    const unsigned int n_local = directors ? 12 : 9;
    if (hessian != nullptr)
      hessian_scatter.start(*hessian, discretization.elements().size(), n_local);

    LocalVector                          g, g_dissipative;
    LocalMatrix                          H;
    FullMatrix<double>                   cell_matrix(n_local, n_local);
    std::vector<types::global_dof_index> dof_vector(n_local);
    double                               value    = 0.;
    const auto                          &elements = discretization.elements();
    for_each_element(
      u,
      predictor,
      previous,
      [&](const ElementState &state) {
        // One memset each: zeroing H row by row took 12 short `rep stos` per element
        // (GCC's choice for 96 bytes), 3 % of the swinging sheet's run time.
        std::memset(g.data(), 0, sizeof(g));
        if (hessian != nullptr)
          std::memset(H.data(), 0, sizeof(H));
        const auto &element = elements[state.index];
        const bool  timed   = state.index % timing_stride == 0;
        for (unsigned int k = 0; k < element_terms.size(); ++k)
          {
            const Clock::time_point start = timed ? Clock::now() : Clock::time_point();
            if (dissipative_gradient != nullptr &&
                element_terms[k]->kind() == TermKind::dissipative)
              {
                // Its part kept apart too (on the displacement dofs: damping has no
                // angle part).
                g_dissipative.fill(0.);
                element_terms[k]->add_to_step(
                  state, step, value, &g_dissipative, hessian != nullptr ? &H : nullptr);
                for (unsigned int i = 0; i < n_local; ++i)
                  g[i] += g_dissipative[i];
                for (unsigned int i = 0; i < 9; ++i)
                  (*dissipative_gradient)[element.local_dofs[i]] += g_dissipative[i];
              }
            else
              element_terms[k]->add_to_step(state,
                                            step,
                                            value,
                                            gradient != nullptr ? &g : nullptr,
                                            hessian != nullptr ? &H : nullptr);
            if (timed)
              seconds[k] +=
                timing_stride * std::max(seconds_since(start) - timing_overhead, 0.);
          }

        std::copy(element.dofs.begin(), element.dofs.end(), dof_vector.begin());
        if (directors)
          std::copy(element.angle_dofs.begin(),
                    element.angle_dofs.end(),
                    dof_vector.begin() + 9);
        if (gradient != nullptr)
          {
            for (unsigned int i = 0; i < 9; ++i)
              gradient_sums.add(element.local_dofs[i], g[i]);
            if (directors)
              for (unsigned int i = 0; i < 3; ++i)
                gradient_sums.add(element.angle_local_dofs[i], g[9 + i]);
          }
        if (hessian != nullptr)
          {
            if (!hessian_scatter.add(
                  state.index, dof_vector, &H[0][0], H[0].size(), constraints))
              {
                for (unsigned int i = 0; i < n_local; ++i)
                  for (unsigned int j = 0; j < n_local; ++j)
                    cell_matrix(i, j) = H[i][j];
                constraints.distribute_local_to_global(cell_matrix, dof_vector, *hessian);
              }
          }
      },
      hessian != nullptr ? step.linearised_from : nullptr);

    if (gradient != nullptr)
      gradient_sums.add_to(*gradient, constraints);

    for (unsigned int k = 0; k < global_terms.size(); ++k)
      {
        const unsigned int term = element_terms.size() + k;
        if (assemblers[term] != all_terms[term])
          continue; // its host adds it
        const Clock::time_point start = Clock::now();
        value += global_terms[k]->add_to_step(
          u, step, constraints, gradient, hessian, dissipative_gradient);
        seconds[term] += seconds_since(start);
      }

    if (gradient != nullptr)
      gradient->compress(VectorOperation::add);
    if (hessian != nullptr)
      {
        // Unit diagonal on the unused (constrained) angle-component dofs.
        hessian_scatter.add_to_diagonal(owned_unused_dofs, 1.);
        hessian->compress(VectorOperation::add);
      }
    return Utilities::MPI::sum(value, discretization.get_communicator());
  }


  void
  Model::dissipative_gradient(const VectorType &u,
                              const StepTerms  &step,
                              RankVector       &gradient) const
  {
    gradient.assign(n_relevant_dofs, 0.);
    const bool element_dissipation =
      std::any_of(element_terms.begin(), element_terms.end(), [](const auto &term) {
        return term->kind() == TermKind::dissipative;
      });
    if (element_dissipation)
      {
        LocalVector g;
        const auto &elements = discretization.elements();
        for_each_element(u, nullptr, step.previous, [&](const ElementState &state) {
          g.fill(0.);
          double value = 0.;
          for (const auto &term : element_terms)
            if (term->kind() == TermKind::dissipative)
              term->add_to_step(state, step, value, &g, nullptr);
          const auto &element = elements[state.index];
          for (unsigned int i = 0; i < 9; ++i)
            gradient[element.local_dofs[i]] += g[i];
        });
      }
    // Each term alone (a host's other parts are not wanted here).
    const AffineConstraints<double> none;
    for (const auto &term : global_terms)
      if (term->kind() == TermKind::dissipative)
        term->add_to_step(u, step, none, nullptr, nullptr, &gradient);
  }


  double
  Model::work(const RankVector &force, const VectorType &ghosted) const
  {
    AssertDimension(force.size(), n_relevant_dofs);
    const double *values = ghosted_values(ghosted, n_relevant_dofs);
    double        local  = 0.;
    for (unsigned int i = 0; i < n_relevant_dofs; ++i)
      local += force[i] * values[i];
    return Utilities::MPI::sum(local, discretization.get_communicator());
  }


  double
  Model::dissipated_work(const VectorType &u,
                         const StepTerms  &step,
                         const VectorType &increment) const
  {
    RankVector gradient;
    dissipative_gradient(u, step, gradient);
    return work(gradient, increment);
  }


  void
  Model::elastic_forces(const VectorType &u, VectorType &forces) const
  {
    add_forces(u, StepTerms(), {TermKind::elastic}, forces);
  }


  void
  Model::static_forces(const VectorType &u,
                       const StepTerms  &step,
                       VectorType       &forces) const
  {
    add_forces(u,
               step,
               {TermKind::elastic, TermKind::potential, TermKind::constraint},
               forces);
  }


  void
  Model::step_forces(const VectorType &u, const StepTerms &step, VectorType &forces) const
  {
    std::vector<TermKind> kinds = {TermKind::elastic,
                                   TermKind::potential,
                                   TermKind::constraint};
    if (step.inertia_weight > 0.)
      kinds.push_back(TermKind::kinetic);
    if (step.damping_weight > 0.)
      kinds.push_back(TermKind::dissipative);
    add_forces(u, step, kinds, forces);
  }


  void
  Model::add_forces(const VectorType            &u,
                    const StepTerms             &step,
                    const std::vector<TermKind> &kinds,
                    VectorType                  &forces) const
  {
    const auto wanted = [&kinds](const TermKind kind) {
      return std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
    };
    forces = 0.;
    LocalVector                          g;
    std::vector<types::global_dof_index> dofs;
    std::vector<double>                  values;
    const auto                          &elements = discretization.elements();
    for_each_element(u, step.predictor, step.previous, [&](const ElementState &state) {
      g.fill(0.);
      for (const auto &term : element_terms)
        if (wanted(term->kind()))
          {
            double value = 0.;
            term->add_to_step(state, step, value, &g, nullptr);
          }
      const auto &element = elements[state.index];
      dofs.assign(element.dofs.begin(), element.dofs.end());
      values.assign(g.begin(), g.begin() + 9);
      if (directors)
        for (unsigned int i = 0; i < 3; ++i)
          {
            dofs.push_back(element.angle_dofs[i]);
            values.push_back(g[9 + i]);
          }
      forces.add(dofs, values);
    });
    const AffineConstraints<double> none;
    for (const auto &term : global_terms)
      if (wanted(term->kind()))
        term->add_to_step(u, step, none, &forces, nullptr, nullptr);
    forces.compress(VectorOperation::add);
  }


  Energies
  Model::energies(const VectorType &u,
                  const VectorType &v,
                  RankVector       *damping_force) const
  {
    std::vector<double> local(all_terms.size(), 0.);
    if (damping_force != nullptr)
      damping_force->assign(n_relevant_dofs, 0.);
    const bool element_forces =
      damping_force != nullptr &&
      std::any_of(element_terms.begin(), element_terms.end(), [](const auto &term) {
        return term->kind() == TermKind::dissipative;
      });
    // The damping force is the dissipative terms' gradient with w_d = 1, u_n = u - v.
    StepTerms forces;
    forces.damping_weight = 1.;
    std::array<double, 9> v_e, centre_e;
    LocalVector           g;
    const auto           &elements = discretization.elements();
    for_each_element(u, nullptr, nullptr, [&](const ElementState &state) {
      const auto &element = elements[state.index];
      discretization.gather(v, element, v_e);
      for (unsigned int k = 0; k < element_terms.size(); ++k)
        local[k] += element_terms[k]->energy(state, v_e);
      if (element_forces)
        {
          for (unsigned int i = 0; i < 9; ++i)
            centre_e[i] = state.u[i] - v_e[i];
          const ElementState moving{state.index,
                                    state.reference,
                                    state.rest,
                                    state.x,
                                    state.u,
                                    state.predictor,
                                    centre_e,
                                    state.psi};
          g.fill(0.);
          double unused = 0.;
          for (const auto &term : element_terms)
            if (term->kind() == TermKind::dissipative)
              term->add_to_step(moving, forces, unused, &g, nullptr);
          for (unsigned int i = 0; i < 9; ++i)
            (*damping_force)[element.local_dofs[i]] += g[i];
        }
    });
    // A hosted term's force comes with its host's.
    for (unsigned int k = 0; k < global_terms.size(); ++k)
      {
        const unsigned int term = element_terms.size() + k;
        local[term] += global_terms[k]->energy(
          u, v, assemblers[term] == all_terms[term] ? damping_force : nullptr);
      }

    Energies result;
    result.terms = local;
    MPI_Allreduce(MPI_IN_PLACE,
                  result.terms.data(),
                  result.terms.size(),
                  MPI_DOUBLE,
                  MPI_SUM,
                  discretization.get_communicator());
    for (unsigned int k = 0; k < all_terms.size(); ++k)
      switch (all_terms[k]->kind())
        {
          case TermKind::kinetic:
            result.kinetic += result.terms[k];
            break;
          case TermKind::elastic:
            result.elastic += result.terms[k];
            break;
          case TermKind::potential:
          case TermKind::constraint:
            result.potential += result.terms[k];
            break;
          case TermKind::dissipative:
            break;
        }
    return result;
  }


  void
  Model::prepare_step(const VectorType &u_n)
  {
    for (Term *term : all_terms)
      term->prepare_step(u_n);
  }


  void
  Model::commit_step(const VectorType &u, VectorType &u_owned)
  {
    for (Term *term : all_terms)
      term->commit_step(u, u_owned);
  }


  bool
  Model::caps_steps() const
  {
    return std::any_of(all_terms.begin(), all_terms.end(), [](const Term *term) {
      return term->caps_steps();
    });
  }


  double
  Model::largest_step(const VectorType &u, const VectorType &direction) const
  {
    double alpha = 1.;
    for (const Term *term : all_terms)
      if (term->caps_steps())
        alpha = std::min(alpha, term->step_cap(u, direction));
    return Utilities::MPI::min(alpha, discretization.get_communicator());
  }


  std::pair<double, double>
  Model::area_ratio_range(const VectorType &u) const
  {
    // The strain measures' area ratio needs no material.
    const MembraneStiffness geometry;
    std::array<double, 9>   u_e;
    double                  smallest = std::numeric_limits<double>::max(), largest = 0.;
    const auto             &elements = discretization.elements();
    for (unsigned int e = 0; e < elements.size(); ++e)
      {
        const TrianglePositions x = discretization.current_positions(elements[e], u, u_e);
        const double ratio = membrane_strain_stress(geometry, rest[e], x).area_ratio;
        // NaN: smallest -1 and largest infinite, so that both checks catch it.
        smallest = std::min(smallest, std::isfinite(ratio) ? ratio : -1.);
        largest =
          std::max(largest,
                   std::isfinite(ratio) ? ratio
                                        : std::numeric_limits<double>::infinity());
      }
    return {Utilities::MPI::min(smallest, discretization.get_communicator()),
            Utilities::MPI::max(largest, discretization.get_communicator())};
  }


  std::vector<CellField>
  Model::cell_fields(const VectorType &u) const
  {
    const MembraneStiffness geometry; // the Green strain's norm needs no material
    std::vector<CellField>  fields(1, CellField{"green_strain", {}});
    std::array<double, 9>   u_e;
    const auto             &elements = discretization.elements();
    for (unsigned int e = 0; e < elements.size(); ++e)
      {
        const TrianglePositions x = discretization.current_positions(elements[e], u, u_e);
        fields[0].values.push_back(
          membrane_strain_stress(geometry, rest[e], x).green_strain_norm);
      }
    for (const Term *term : all_terms)
      if (const auto *source = dynamic_cast<const FieldSource *>(term))
        source->add_cell_fields(discretization, u, fields);
    return fields;
  }
} // namespace clothsim::physics
