// The model's energy report (statistics.csv: the columns beyond kinetic, elastic and
// potential energy, the contact and drape figures of a state).

#include "scene/cloth_model.h"

#include <deal.II/base/mpi.h>

#include "mesh/projected_area.h"

#include <algorithm>

namespace clothsim
{
  std::vector<std::string>
  ClothModel::energy_columns() const
  {
    // Kinetic energy has its own column already; the dissipative terms share one.
    std::vector<std::string> columns;
    for (const physics::Term *term : model->terms())
      if (term->kind() != physics::TermKind::kinetic &&
          std::find(columns.begin(), columns.end(), term->report_column()) ==
            columns.end())
        columns.push_back(term->report_column());
    // Contact: the smallest distance from an obstacle of what contact keeps off them
    // and of the whole surface (m), then per obstacle the force on the cloth (N) and the
    // vertices and pairs within the thickness.
    if (contact != nullptr)
      {
        columns.push_back("contact_min_distance");
        columns.push_back("contact_surface_distance");
        for (const physics::Obstacle &obstacle : contact->get_obstacles())
          {
            std::string name = obstacle.name();
            std::replace(name.begin(), name.end(), ' ', '_');
            for (const char *part : {"_force_x", "_force_y", "_force_z", "_contacts"})
              columns.push_back(name + part);
          }
        if (adapts_stiffness())
          columns.push_back("contact_barrier_stiffness");
      }
    // Self-contact: the smallest distance between primitives that share no vertex (m;
    // at most ten times the thickness: none closer), and the pairs within the thickness.
    // With 'Adaptive barrier stiffness', each contact's a_b as raised (m/s²).
    if (self_contact != nullptr)
      for (const char *column : {"self_contact_min_distance", "self_contact_pairs"})
        columns.push_back(column);
    if (self_contact != nullptr && adapts_stiffness())
      columns.push_back("self_contact_barrier_stiffness");
    if (parameters.output.drape_disc_radius > 0.)
      for (const char *column : {"projected_area", "drape_coefficient"})
        columns.push_back(column);
    if (parameters.output.check_intersections)
      columns.push_back("intersecting_pairs");
    // The work done on the cloth by the prescribed motion so far (J), and the energy
    // the strain limit added, filled in by the steppers (StepperCore::reported); last,
    // so that the model's columns keep their places.
    if (has_prescribed_motion())
      columns.push_back("prescribed_work");
    // The energy Provot's strain limit has added by its corrections so far (J).
    if (has_strain_limit())
      columns.push_back("strain_limit_energy");
    // The energy the adaptive barrier stiffness's raises added (J).
    if (adapts_stiffness())
      columns.push_back("stiffness_raise_energy");
    return columns;
  }


  EnergyReport
  ClothModel::energies(const VectorType &u,
                       const VectorType &v,
                       const double      dissipated) const
  {
    return add_step_report(u, report(model->energies(u, v), dissipated));
  }


  EnergyReport
  ClothModel::energies(const VectorType    &u,
                       const VectorType    &v,
                       const double         dissipated,
                       physics::RankVector &damping_force) const
  {
    return add_step_report(u, report(model->energies(u, v, &damping_force), dissipated));
  }


  EnergyReport
  ClothModel::add_step_report(const VectorType &u, EnergyReport energies) const
  {
    // The contact, drape and intersection columns are the last ones but the steppers'
    // (energy_columns()).
    const double       drape_radius = parameters.output.drape_disc_radius;
    const bool         intersecting = parameters.output.check_intersections;
    const unsigned int adaptive     = adapts_stiffness() ? 1 : 0;
    const double       a_b          = parameters.contact.barrier_acceleration;
    std::size_t        column =
      energies.columns.size() - (drape_radius > 0. ? 2 : 0) - (intersecting ? 1 : 0) -
      (self_contact != nullptr ? 2 + adaptive : 0) - (has_prescribed_motion() ? 1 : 0) -
      (has_strain_limit() ? 1 : 0) - adaptive;
    if (contact != nullptr)
      {
        const physics::ObstacleContact::Report contacts =
          contact->report(u, contact->time_of_state());
        column -= 2 + 4 * contacts.forces.size() + adaptive;
        energies.columns[column++] = contacts.min_distance;
        energies.columns[column++] = contacts.min_surface_distance;
        for (unsigned int o = 0; o < contacts.forces.size(); ++o)
          {
            for (unsigned int c = 0; c < 3; ++c)
              energies.columns[column++] = contacts.forces[o][c];
            energies.columns[column++] = contacts.contacts[o];
          }
        if (adaptive)
          energies.columns[column++] = a_b * contact->barrier_stiffness().scale();
      }
    if (self_contact != nullptr)
      {
        const double                       range = 10. * parameters.contact.thickness;
        const physics::SelfContact::Report pairs = self_contact->report(u, range);
        energies.columns[column++]               = std::min(pairs.min_distance, range);
        energies.columns[column++]               = pairs.pairs;
        if (adaptive)
          energies.columns[column++] = a_b * self_contact->barrier_stiffness().scale();
      }
    if (drape_radius == 0. && !intersecting)
      return energies;
    // Both measure the whole mesh on rank 0 (0 elsewhere, summed over ranks).
    const MPI_Comm                           communicator = get_communicator();
    const std::vector<physics::MeshTriangle> triangles    = triangles_on_root(u);
    if (drape_radius > 0.)
      {
        double area = 0.;
        if (Utilities::MPI::this_mpi_process(communicator) == 0)
          {
            std::vector<std::array<Point<2>, 3>> shadows;
            for (const physics::MeshTriangle &triangle : triangles)
              {
                std::array<Point<2>, 3> shadow;
                for (unsigned int v = 0; v < 3; ++v)
                  shadow[v] = Point<2>(triangle.corners[v][0], triangle.corners[v][1]);
                shadows.push_back(shadow);
              }
            area = mesh::projected_area(shadows);
          }
        area                       = Utilities::MPI::sum(area, communicator);
        const double disc          = numbers::PI * drape_radius * drape_radius;
        energies.columns[column++] = area;
        energies.columns[column++] =
          (area - disc) / (discretization.reference_area() - disc);
      }
    if (intersecting)
      {
        const double pairs =
          Utilities::MPI::this_mpi_process(communicator) == 0
            ? static_cast<double>(physics::intersecting_pairs(triangles).size())
            : 0.;
        energies.columns[column++] = Utilities::MPI::sum(pairs, communicator);
      }
    return energies;
  }


  std::vector<physics::MeshTriangle>
  ClothModel::triangles_on_root(const VectorType &u) const
  {
    // Per triangle: 9 coordinates, then its vertices' ids (their x dofs, exact in a
    // double below 2^53).
    std::vector<double>   values;
    std::array<double, 9> u_e;
    for (const auto &element : discretization.elements())
      {
        for (const Point<3> &x : discretization.current_positions(element, u, u_e))
          values.insert(values.end(), {x[0], x[1], x[2]});
        for (unsigned int v = 0; v < 3; ++v)
          values.push_back(static_cast<double>(element.dofs[3 * v]));
      }
    const auto all = Utilities::MPI::gather(get_communicator(), values, 0);
    std::vector<physics::MeshTriangle> triangles;
    for (const std::vector<double> &part : all)
      for (std::size_t k = 0; k + 12 <= part.size(); k += 12)
        {
          physics::MeshTriangle triangle;
          for (unsigned int v = 0; v < 3; ++v)
            {
              triangle.corners[v] =
                Point<3>(part[k + 3 * v], part[k + 3 * v + 1], part[k + 3 * v + 2]);
              triangle.vertices[v] =
                static_cast<types::global_dof_index>(part[k + 9 + v]);
            }
          triangles.push_back(triangle);
        }
    return triangles;
  }


  EnergyReport
  ClothModel::report(const physics::Energies &energies, const double dissipated) const
  {
    const std::vector<std::string> columns = energy_columns();
    EnergyReport                   report{energies.kinetic,
                        energies.elastic,
                        energies.potential,
                        std::vector<double>(columns.size(), 0.)};
    const auto                    &terms = model->terms();
    for (unsigned int k = 0; k < terms.size(); ++k)
      {
        const auto column =
          std::find(columns.begin(), columns.end(), terms[k]->report_column());
        if (column == columns.end())
          continue;
        report.columns[column - columns.begin()] =
          terms[k]->kind() == physics::TermKind::dissipative
            ? dissipated
            : terms[k]->reported_value(energies.terms[k]);
      }
    return report;
  }
} // namespace clothsim
