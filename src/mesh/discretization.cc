#include "mesh/discretization.h"

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria_description.h>

#include "mesh/element_matrix_scatter.h"
#include "mesh/ghosted_values.h"

#include <algorithm>
#include <map>
#include <set>

namespace clothsim::mesh
{
  namespace
  {
    // Unit normal of a triangle with the given vertices.
    Tensor<1, 3>
    unit_normal(const Point<3> &x0, const Point<3> &x1, const Point<3> &x2)
    {
      const Tensor<1, 3> N = cross_product_3d(x1 - x0, x2 - x0);
      return N / N.norm();
    }

    // |T̄| = ½ √det Ā with Ā the metric of the edge basis X1 - X0, X2 - X0 (0 if
    // degenerate); the same formula as physics::membrane_rest_data.
    double
    triangle_area(const std::array<Point<3>, 3> &X)
    {
      const Tensor<1, 3> a = X[1] - X[0], b = X[2] - X[0];
      Tensor<2, 2>       metric;
      metric[0][0]     = a * a;
      metric[0][1]     = a * b;
      metric[1][0]     = b * a;
      metric[1][1]     = b * b;
      const double det = determinant(metric);
      return det > 0. ? 0.5 * std::sqrt(det) : 0.;
    }
  } // namespace


  Discretization::Discretization(const MPI_Comm             communicator,
                                 const Triangulation<2, 3> &serial_mesh,
                                 const MeshSetup           &setup)
    : communicator(communicator)
    , setup(setup)
    , triangulation(
        std::make_unique<parallel::fullydistributed::Triangulation<2, 3>>(communicator))
    , fe(setup.directors ? std::make_unique<FESystem<2, 3>>(FE_SimplexP<2, 3>(1),
                                                            3,
                                                            FE_SimplexP<2, 3>(2),
                                                            1)
                         : std::make_unique<FESystem<2, 3>>(FE_SimplexP<2, 3>(1), 3))
    , mapping(std::make_unique<MappingFE<2, 3>>(FE_SimplexP<2, 3>(1)))
    , dof_handler(std::make_unique<DoFHandler<2, 3>>())
  {
    build_mesh(serial_mesh);
    setup_dofs();
    if (setup.directors)
      setup_edges();
  }


  Discretization::~Discretization() = default;


  types::global_dof_index
  Discretization::n_dofs() const
  {
    return dof_handler->n_dofs();
  }


  types::global_cell_index
  Discretization::n_triangles() const
  {
    return triangulation->n_global_active_cells();
  }


  void
  Discretization::build_mesh(const Triangulation<2, 3> &serial_mesh)
  {
    // Every rank holds the same coarse mesh; refine it, partition it with METIS
    // (deterministic), and keep only this rank's part plus a ghost layer.
    Triangulation<2, 3> refined;
    refined.copy_triangulation(serial_mesh);
    std::unique_ptr<Manifold<2, 3>> surface;
    if (setup.surface == "cylinder")
      surface = std::make_unique<CylindricalManifold<2, 3>>(setup.axis, setup.center);
    else if (setup.surface == "sphere")
      surface = std::make_unique<SphericalManifold<2, 3>>(setup.center);
    if (surface != nullptr)
      {
        refined.set_all_manifold_ids(1);
        refined.set_manifold(1, *surface);
      }
    refined.refine_global(setup.global_refinements);
    refined.reset_all_manifolds();
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    if (n_ranks > 1)
      GridTools::partition_triangulation(n_ranks, refined);
    const auto description =
      TriangulationDescription::Utilities::create_description_from_triangulation(
        refined, communicator);
    // The distributed triangulation repeats the refinement from the coarse cells: it
    // needs the surface too.
    if (surface != nullptr)
      triangulation->set_manifold(1, *surface);
    triangulation->create_triangulation(description);
  }


  void
  Discretization::setup_dofs()
  {
    dof_handler->reinit(*triangulation);
    dof_handler->distribute_dofs(*fe);
    locally_owned_dofs = dof_handler->locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(*dof_handler, locally_relevant_dofs);
    owned_prototype.reinit(locally_owned_dofs, communicator);
    ghosted_prototype.reinit(locally_owned_dofs, locally_relevant_dofs, communicator);
    ghost_import =
      std::make_unique<const Epetra_Import>(ghosted_prototype.trilinos_vector().Map(),
                                            owned_prototype.trilinos_vector().Map());
    vertex_count = DoFTools::count_dofs_per_fe_component(*dof_handler)[0];

    // local dof -> (vertex, component) for the displacements (the P1 base element's dof
    // k sits on vertex k); the angle component (4th) is handled in setup_edges().
    dof_vertex_component.resize(fe->n_dofs_per_cell());
    for (unsigned int i = 0; i < fe->n_dofs_per_cell(); ++i)
      {
        const auto component_index = fe->system_to_component_index(i);
        dof_vertex_component[i]    = {component_index.second, component_index.first};
      }

    VectorType prototype;
    initialize_ghosted(prototype);
    std::vector<types::global_dof_index> dof_indices(fe->n_dofs_per_cell());
    element_table.clear();
    std::vector<types::global_dof_index> owned_displacements;
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dof_indices);
          Element element;
          for (unsigned int i = 0; i < fe->n_dofs_per_cell(); ++i)
            {
              const auto [vertex, component] = dof_vertex_component[i];
              if (component < 3)
                element.dofs[3 * vertex + component] = dof_indices[i];
            }
          for (unsigned int i = 0; i < 9; ++i)
            {
              element.local_dofs[i] = local_index(prototype, element.dofs[i]);
              if (locally_owned_dofs.is_element(element.dofs[i]))
                owned_displacements.push_back(element.dofs[i]);
            }
          for (unsigned int v = 0; v < 3; ++v)
            element.reference[v] = cell->vertex(v);
          element.area = triangle_area(element.reference);
          for (unsigned int line = 0; line < 3; ++line)
            {
              unsigned int v = 0; // the vertex opposite the line
              while (cell->vertex_index(v) == cell->line(line)->vertex_index(0) ||
                     cell->vertex_index(v) == cell->line(line)->vertex_index(1))
                ++v;
              // A boundary edge by its triangle; an inner one by the triangle of
              // the lower rank, or with the lower id on one rank.
              element.counts_edge[v] =
                cell->at_boundary(line) ||
                (cell->neighbor(line)->is_locally_owned()
                   ? cell->id() < cell->neighbor(line)->id()
                   : cell->subdomain_id() < cell->neighbor(line)->subdomain_id());
            }
          element_table.push_back(element);
        }
    std::sort(owned_displacements.begin(), owned_displacements.end());
    owned_displacements.erase(std::unique(owned_displacements.begin(),
                                          owned_displacements.end()),
                              owned_displacements.end());
    displacement_dofs = IndexSet(dof_handler->n_dofs());
    displacement_dofs.add_indices(owned_displacements.begin(), owned_displacements.end());
    displacement_dofs.compress();
  }


  void
  Discretization::setup_edges()
  {
    // The angle component's P2 dofs: k < 3 sits on vertex k (unused), k >= 3 on line
    // k - 3 of the cell.
    std::map<types::global_dof_index, unsigned int> slot_of_dof;
    std::set<types::global_dof_index>               unused_set;
    std::vector<types::global_dof_index>            dof_indices(fe->n_dofs_per_cell());
    VectorType                                      prototype;
    initialize_ghosted(prototype);
    edge_table.clear();
    unsigned int e = 0;
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(dof_indices);
          for (unsigned int i = 0; i < fe->n_dofs_per_cell(); ++i)
            {
              const auto [component, index] = fe->system_to_component_index(i);
              if (component == 3 && index < 3)
                unused_set.insert(dof_indices[i]);
            }
          if (!cell->is_locally_owned())
            continue;

          Element           &element = element_table[e++];
          const Tensor<1, 3> normal =
            unit_normal(cell->vertex(0), cell->vertex(1), cell->vertex(2));
          for (unsigned int i = 0; i < fe->n_dofs_per_cell(); ++i)
            {
              const auto [component, index] = fe->system_to_component_index(i);
              if (component != 3 || index < 3)
                continue;
              const unsigned int line = index - 3;
              // The triangle's edge opposite vertex v is this line.
              unsigned int v = 0;
              while (cell->vertex_index(v) == cell->line(line)->vertex_index(0) ||
                     cell->vertex_index(v) == cell->line(line)->vertex_index(1))
                ++v;
              const unsigned int next = (v + 1) % 3, after = (v + 2) % 3;
              const bool forward    = precedes(cell->vertex(next), cell->vertex(after));
              element.angle_dofs[v] = dof_indices[i];
              element.angle_local_dofs[v] = local_index(prototype, dof_indices[i]);
              element.edge_signs[v]       = forward ? 1. : -1.;

              auto [slot, inserted] =
                slot_of_dof.emplace(dof_indices[i], edge_table.size());
              element.edge_slots[v] = slot->second;
              if (!inserted)
                continue;
              // Rest director: the bisector of the two rest normals, or the normal on
              // the boundary (ψ̄ = 0 then gives the rest curvature B̄).
              Edge edge;
              edge.angle_dof = dof_indices[i];
              const std::array<unsigned int, 2> ends =
                forward ? std::array<unsigned int, 2>{{next, after}}
                        : std::array<unsigned int, 2>{{after, next}};
              for (unsigned int k = 0; k < 2; ++k)
                {
                  edge.reference_points[k] = cell->vertex(ends[k]);
                  for (unsigned int c = 0; c < 3; ++c)
                    edge.vertex_dofs[k][c] = element.dofs[3 * ends[k] + c];
                }
              edge.rest_director = normal;
              if (!cell->at_boundary(line))
                {
                  const auto         neighbor = cell->neighbor(line);
                  const Tensor<1, 3> bisector = normal + unit_normal(neighbor->vertex(0),
                                                                     neighbor->vertex(1),
                                                                     neighbor->vertex(2));
                  AssertThrow(bisector.norm() > 1e-8,
                              ExcMessage("two neighbouring triangles of the mesh are "
                                         "folded onto each other"));
                  edge.rest_director = bisector / bisector.norm();
                }
              edge_table.push_back(edge);
            }
        }
    unused.assign(unused_set.begin(), unused_set.end());
  }


  void
  Discretization::initialize_owned(VectorType &vector) const
  {
    vector = VectorType(owned_prototype); // a copy shares the prototype's map
  }


  void
  Discretization::initialize_ghosted(VectorType &vector) const
  {
    vector = VectorType(ghosted_prototype);
  }


  void
  Discretization::import_ghosts(const VectorType &owned, VectorType &ghosted) const
  {
    const Epetra_MultiVector &from = owned.trilinos_vector();
    Epetra_MultiVector       &to   = ghosted.trilinos_vector();
    if (from.Map().DataPtr() != owned_prototype.trilinos_vector().Map().DataPtr() ||
        to.Map().DataPtr() != ghosted_prototype.trilinos_vector().Map().DataPtr())
      {
        ghosted = owned;
        return;
      }
    const int ierr = to.Import(from, *ghost_import, Insert);
    AssertThrow(ierr == 0, ExcTrilinosError(ierr));
  }


  void
  Discretization::initialize_matrix(
    MatrixType                                                     &matrix,
    const AffineConstraints<double>                                &constraints,
    const std::function<void(TrilinosWrappers::SparsityPattern &)> &add_couplings) const
  {
    TrilinosWrappers::SparsityPattern sparsity(locally_owned_dofs,
                                               locally_owned_dofs,
                                               locally_relevant_dofs,
                                               communicator);
    DoFTools::make_sparsity_pattern(*dof_handler, sparsity, constraints, false);
    if (add_couplings)
      add_couplings(sparsity);
    sparsity.compress();
    matrix.reinit(sparsity);
    ElementMatrixScatter::sparsity_changed();
  }


  void
  Discretization::gather(const VectorType      &ghosted,
                         const Element         &element,
                         std::array<double, 9> &values) const
  {
    const double *local = ghosted_values(ghosted, locally_relevant_dofs.n_elements());
    for (unsigned int i = 0; i < 9; ++i)
      values[i] = local[element.local_dofs[i]];
  }


  std::array<double, 3>
  Discretization::angles(const VectorType &ghosted, const Element &element) const
  {
    const double *local = ghosted_values(ghosted, locally_relevant_dofs.n_elements());
    return {{local[element.angle_local_dofs[0]],
             local[element.angle_local_dofs[1]],
             local[element.angle_local_dofs[2]]}};
  }


  std::array<Point<3>, 3>
  Discretization::current_positions(const Element         &element,
                                    const VectorType      &u,
                                    std::array<double, 9> &u_e) const
  {
    gather(u, element, u_e);
    std::array<Point<3>, 3> x = element.reference;
    for (unsigned int v = 0; v < 3; ++v)
      for (unsigned int d = 0; d < 3; ++d)
        x[v][d] += u_e[3 * v + d];
    return x;
  }


  double
  Discretization::reference_area() const
  {
    double area = 0.;
    for (const Element &element : element_table)
      area += element.area;
    return Utilities::MPI::sum(area, communicator);
  }


  Point<3>
  Discretization::reference_centroid() const
  {
    Tensor<1, 3> moment;
    double       area = 0.;
    for (const Element &element : element_table)
      {
        for (unsigned int v = 0; v < 3; ++v)
          moment += (element.area / 3.) * element.reference[v];
        area += element.area;
      }
    for (unsigned int d = 0; d < 3; ++d)
      moment[d] = Utilities::MPI::sum(moment[d], communicator);
    return Point<3>(moment / Utilities::MPI::sum(area, communicator));
  }


  double
  Discretization::longest_edge() const
  {
    double longest = 0.;
    for (const Element &element : element_table)
      for (unsigned int v = 0; v < 3; ++v)
        longest = std::max(longest,
                           element.reference[v].distance(element.reference[(v + 1) % 3]));
    return Utilities::MPI::max(longest, communicator);
  }


  double
  Discretization::largest_reference_coordinate() const
  {
    double largest = 0.;
    for (const Element &element : element_table)
      for (unsigned int v = 0; v < 3; ++v)
        for (unsigned int d = 0; d < 3; ++d)
          largest = std::max(largest, std::abs(element.reference[v][d]));
    return Utilities::MPI::max(largest, communicator);
  }


  std::vector<std::array<double, 6>>
  Discretization::vertex_displacements(const VectorType &u) const
  {
    std::vector<std::array<double, 6>> local;
    std::set<types::global_dof_index>  seen;
    for (const Element &element : element_table)
      for (unsigned int v = 0; v < 3; ++v)
        if (locally_owned_dofs.is_element(element.dofs[3 * v]) &&
            seen.insert(element.dofs[3 * v]).second)
          {
            std::array<double, 6> row;
            for (unsigned int d = 0; d < 3; ++d)
              {
                row[d]     = element.reference[v][d];
                row[3 + d] = u(element.dofs[3 * v + d]);
              }
            local.push_back(row);
          }
    const auto gathered = Utilities::MPI::gather(communicator, local, 0);
    std::vector<std::array<double, 6>> all;
    for (const auto &part : gathered)
      all.insert(all.end(), part.begin(), part.end());
    std::sort(all.begin(), all.end(), [](const auto &a, const auto &b) {
      return std::lexicographical_compare(a.begin(),
                                          a.begin() + 3,
                                          b.begin(),
                                          b.begin() + 3);
    });
    return all;
  }


  Discretization::SurfacePiece
  Discretization::surface_piece() const
  {
    // A vertex is identified by its x dof; points are numbered in order of appearance.
    SurfacePiece                                    piece;
    std::map<types::global_dof_index, unsigned int> point_of_dof;
    for (const Element &element : element_table)
      {
        std::array<unsigned int, 3> triangle;
        for (unsigned int v = 0; v < 3; ++v)
          {
            const auto [found, inserted] =
              point_of_dof.emplace(element.dofs[3 * v], piece.points.size());
            if (inserted)
              {
                const Point<3> &X = element.reference[v];
                piece.points.push_back({{X[0], X[1], X[2]}});
                piece.point_dofs.push_back({{element.dofs[3 * v],
                                             element.dofs[3 * v + 1],
                                             element.dofs[3 * v + 2]}});
              }
            triangle[v] = found->second;
          }
        piece.triangles.push_back(triangle);
      }
    return piece;
  }
} // namespace clothsim::mesh
