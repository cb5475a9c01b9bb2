#include "physics/bending_term.h"

namespace clothsim::physics
{
  BendingTerm::BendingTerm(const mesh::Discretization              &discretization,
                           const BendingMaterial                   &material,
                           const std::set<types::global_dof_index> &clamped_angles)
    : ElementTerm("bending", TermKind::elastic)
    , discretization(discretization)
    , material(material)
  {
    for (const auto &edge : discretization.edges())
      {
        references.push_back(edge.rest_director);
        clamped.push_back(clamped_angles.count(edge.angle_dof) > 0);
      }
    const auto &elements = discretization.elements();
    for (unsigned int e = 0; e < elements.size(); ++e)
      rest.push_back(bending_rest_data(material, elements[e].reference, directors(e)));
  }


  EdgeDirectors
  BendingTerm::directors(const unsigned int element) const
  {
    const auto   &data = discretization.elements()[element];
    EdgeDirectors result;
    for (unsigned int i = 0; i < 3; ++i)
      {
        result.reference[i] = references[data.edge_slots[i]];
        result.sign[i]      = data.edge_signs[i];
      }
    return result;
  }


  void
  BendingTerm::add_to_step(const ElementState &element,
                           const StepTerms    &step,
                           double             &value,
                           LocalVector        *gradient,
                           LocalMatrix        *hessian) const
  {
    const EdgeDirectors edge_directors = directors(element.index);
    if (gradient == nullptr && hessian == nullptr)
      {
        value += bending_energy(
          material, rest[element.index], element.x, edge_directors, element.psi);
        return;
      }
    BendingVector g;
    BendingMatrix H;
    value += bending_energy_gradient_hessian(material,
                                             rest[element.index],
                                             element.x,
                                             edge_directors,
                                             element.psi,
                                             step.projected_tangent,
                                             g,
                                             hessian != nullptr ? &H : nullptr);
    add_to_element(g, H, gradient, hessian);
  }


  double
  BendingTerm::energy(const ElementState &element, const std::array<double, 9> &) const
  {
    return bending_energy(
      material, rest[element.index], element.x, directors(element.index), element.psi);
  }


  void
  BendingTerm::commit_step(const VectorType &u, VectorType &u_owned)
  {
    const auto &edges = discretization.edges();
    for (unsigned int k = 0; k < edges.size(); ++k)
      {
        if (clamped[k])
          continue;
        std::array<Point<3>, 2> ends = edges[k].reference_points;
        for (unsigned int j = 0; j < 2; ++j)
          for (unsigned int c = 0; c < 3; ++c)
            ends[j][c] += u(edges[k].vertex_dofs[j][c]);
        references[k] =
          edge_director(ends[0], ends[1], references[k], u(edges[k].angle_dof));
        if (discretization.owned_dofs().is_element(edges[k].angle_dof))
          u_owned[edges[k].angle_dof] = 0.;
      }
    u_owned.compress(VectorOperation::insert);
  }


  std::vector<double>
  BendingTerm::saved_state() const
  {
    std::vector<double> state;
    state.reserve(3 * references.size());
    for (const Tensor<1, 3> &reference : references)
      for (unsigned int c = 0; c < 3; ++c)
        state.push_back(reference[c]);
    return state;
  }


  void
  BendingTerm::restore_state(const std::vector<double> &state)
  {
    AssertThrow(state.size() == 3 * references.size(),
                ExcMessage(
                  "the director references of a checkpoint do not fit the mesh"));
    for (unsigned int k = 0; k < references.size(); ++k)
      for (unsigned int c = 0; c < 3; ++c)
        references[k][c] = state[3 * k + c];
  }


  double
  BendingTerm::step_cap(const VectorType &u, const VectorType &direction) const
  {
    double                alpha = 1.;
    std::array<double, 9> u_e, du_e;
    const auto           &elements = discretization.elements();
    for (unsigned int e = 0; e < elements.size() && alpha > 0.; ++e)
      {
        const auto &element = elements[e];
        discretization.gather(direction, element, du_e);
        std::array<Tensor<1, 3>, 3> dx;
        EdgeAngles                  psi, dpsi;
        for (unsigned int i = 0; i < 3; ++i)
          {
            for (unsigned int c = 0; c < 3; ++c)
              dx[i][c] = du_e[3 * i + c];
          }
        psi   = discretization.angles(u, element);
        dpsi  = discretization.angles(direction, element);
        alpha = tilt_step_bound(material.director_function,
                                discretization.current_positions(element, u, u_e),
                                dx,
                                directors(e),
                                psi,
                                dpsi,
                                alpha);
      }
    return alpha;
  }


  void
  BendingTerm::add_cell_fields(const mesh::Discretization &,
                               const VectorType       &u,
                               std::vector<CellField> &fields) const
  {
    CellField             curvature{"curvature_change", {}};
    std::array<double, 9> u_e;
    const auto           &elements = discretization.elements();
    for (unsigned int e = 0; e < elements.size(); ++e)
      {
        const EdgeAngles psi = discretization.angles(u, elements[e]);
        curvature.values.push_back(
          curvature_change_norm(material,
                                rest[e],
                                discretization.current_positions(elements[e], u, u_e),
                                directors(e),
                                psi));
      }
    fields.push_back(curvature);
  }
} // namespace clothsim::physics
