#pragma once

// The discrete surface: a distributed triangle mesh, the unknowns on it and the element
// tables that every term's cell loop reads.
//
// Unknowns: displacement u = x - X of every vertex (FE_SimplexP(1)^3) and, with shell
// directors, one director angle ψ per edge (physics/bending.h): a fourth component
// FE_SimplexP(2) whose vertex dofs are unused (constrained to zero by the boundary
// conditions), which leaves exactly its one dof per edge. The FESystem's local dofs are
// mapped to (vertex, component) and (edge) once at set-up; an element then carries its 9
// displacement dofs (vertex v, component c at 3v + c), their positions in ghosted
// vectors, its reference vertices and, with directors, its three edges (edge i opposite
// vertex i). Every edge is stored once per rank with its end points in a rank-independent
// order (lexicographic in the reference coordinates) and its rest director (bisector of
// the two rest normals, the normal on the boundary).

#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_Import.h>

#include "mesh/dealii_declarations.h"


#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace clothsim
{
  using namespace dealii;

  using VectorType = TrilinosWrappers::MPI::Vector;
  using MatrixType = TrilinosWrappers::SparseMatrix;

  namespace mesh
  {
    // A rank-independent order of vertices: lexicographic in the reference coordinates.
    inline bool
    precedes(const Point<3> &a, const Point<3> &b)
    {
      for (unsigned int d = 0; d < 3; ++d)
        if (a[d] != b[d])
          return a[d] < b[d];
      return false;
    }

    // How the mesh as read becomes the computational mesh.
    struct MeshSetup
    {
      unsigned int global_refinements = 0;
      // Curved rest surfaces put new vertices onto the exact surface: "flat" (none),
      // "cylinder" (axis through `center` along `axis`), "sphere" (about `center`).
      std::string  surface = "flat";
      Point<3>     center;
      Tensor<1, 3> axis;
      // One director angle per edge (shell bending).
      bool directors = false;
    };

    class Discretization
    {
    public:
      // One locally owned triangle.
      struct Element
      {
        std::array<types::global_dof_index, 9> dofs; // (vertex v, comp. c) at 3v + c
        std::array<int, 9>                     local_dofs; // in ghosted vectors
        std::array<Point<3>, 3>                reference;  // X0, X1, X2, m
        double                                 area;       // |T̄|, m²
        // With directors, edge i (opposite vertex i): its angle dof, its slot in
        // edges(), the sign s_i = ±1 of its global direction against x_{i+2} - x_{i+1}.
        std::array<types::global_dof_index, 3> angle_dofs;
        std::array<int, 3>                     angle_local_dofs; // in ghosted vectors
        std::array<unsigned int, 3>            edge_slots;
        std::array<double, 3>                  edge_signs;
        // Whether this rank counts the edge opposite vertex v in sums over the mesh's
        // edges (each edge by one triangle of one rank).
        std::array<bool, 3> counts_edge;
      };

      // One edge of a locally owned triangle (with directors).
      struct Edge
      {
        types::global_dof_index                               angle_dof;
        std::array<std::array<types::global_dof_index, 3>, 2> vertex_dofs;
        std::array<Point<3>, 2>                               reference_points;
        Tensor<1, 3> rest_director; // unit, perpendicular to no particular edge yet
      };

      // Builds the distributed mesh from `serial_mesh` (the same on every rank) and
      // distributes the dofs. Collective.
      Discretization(const MPI_Comm             communicator,
                     const Triangulation<2, 3> &serial_mesh,
                     const MeshSetup           &setup);
      ~Discretization();

      MPI_Comm
      get_communicator() const
      {
        return communicator;
      }
      const DoFHandler<2, 3> &
      get_dof_handler() const
      {
        return *dof_handler;
      }
      const MappingFE<2, 3> &
      get_mapping() const
      {
        return *mapping;
      }
      const FESystem<2, 3> &
      get_fe() const
      {
        return *fe;
      }
      const IndexSet &
      owned_dofs() const
      {
        return locally_owned_dofs;
      }
      const IndexSet &
      relevant_dofs() const
      {
        return locally_relevant_dofs;
      }
      // The owned displacement dofs (all owned dofs without directors).
      const IndexSet &
      owned_displacement_dofs() const
      {
        return displacement_dofs;
      }
      // The owned director-angle dofs (none without directors).
      IndexSet
      owned_angle_dofs() const
      {
        IndexSet angles = locally_owned_dofs;
        angles.subtract_set(displacement_dofs);
        return angles;
      }
      types::global_dof_index
      n_dofs() const;
      unsigned int
      n_vertices() const
      {
        return vertex_count;
      }
      types::global_cell_index
      n_triangles() const;
      bool
      has_directors() const
      {
        return setup.directors;
      }
      // (vertex, component) of each local dof of a cell; component 3 is the angle,
      // whose P2 dof k >= 3 sits on line k - 3 of the cell.
      const std::vector<std::pair<unsigned int, unsigned int>> &
      local_dof_vertex_component() const
      {
        return dof_vertex_component;
      }

      const std::vector<Element> &
      elements() const
      {
        return element_table;
      }
      const std::vector<Edge> &
      edges() const
      {
        return edge_table;
      }
      // The angle component's vertex dofs that no element uses (locally relevant).
      const std::vector<types::global_dof_index> &
      unused_dofs() const
      {
        return unused;
      }

      // Zeroed vectors of the owned and of the ghosted (locally relevant) layout. All
      // vectors made here share one Epetra map per layout, so that import_ghosts() and
      // deal.II's checks of equal layouts compare pointers, not index lists.
      void
      initialize_owned(VectorType &vector) const;
      void
      initialize_ghosted(VectorType &vector) const;
      // ghosted = owned (its owned entries and the ghosts from their owners) through one
      // Epetra_Import built at set-up. deal.II's assignment builds a new Import at every
      // call, with a global-to-local lookup per entry and a round of messages (4 % of a
      // second rank's time on the swing, N = 161). Vectors not made by the two
      // functions above are assigned by deal.II.
      void
      import_ghosts(const VectorType &owned, VectorType &ghosted) const;
      // The cells' couplings through `constraints`, plus any that `add_couplings` adds
      // (terms that couple dofs sharing no cell, e.g. cross springs).
      void
      initialize_matrix(MatrixType                      &matrix,
                        const AffineConstraints<double> &constraints,
                        const std::function<void(TrilinosWrappers::SparsityPattern &)>
                          &add_couplings) const;

      // The element's 9 displacement values from a ghosted vector.
      void
      gather(const VectorType      &ghosted,
             const Element         &element,
             std::array<double, 9> &values) const;

      // With directors, the element's edge angles ψ_i (rad) from a ghosted vector.
      std::array<double, 3>
      angles(const VectorType &ghosted, const Element &element) const;

      // Current vertex positions x = X + u of an element; u_e gets its displacements.
      std::array<Point<3>, 3>
      current_positions(const Element         &element,
                        const VectorType      &u,
                        std::array<double, 9> &u_e) const;

      // Σ |T̄| over all triangles, m² (summed over ranks).
      double
      reference_area() const;

      // The area-weighted centroid of the reference surface, m (summed over ranks).
      Point<3>
      reference_centroid() const;

      // The longest edge of the (refined) mesh, m (over all ranks).
      double
      longest_edge() const;

      // The largest coordinate magnitude max |X_i| of the reference surface, m (over all
      // ranks): the scale of round-off in positions.
      double
      largest_reference_coordinate() const;

      // Every vertex's reference position and displacement (X, Y, Z, ux, uy, uz) from `u`
      // (ghosted), sorted by reference position, on rank 0 (empty elsewhere).
      std::vector<std::array<double, 6>>
      vertex_displacements(const VectorType &u) const;

      // This rank's triangles as a connected piece for output: the vertices they use
      // (reference positions), three indices per triangle (in the order of elements()),
      // and each vertex's three displacement dofs.
      struct SurfacePiece
      {
        std::vector<std::array<double, 3>>                  points;
        std::vector<std::array<unsigned int, 3>>            triangles;
        std::vector<std::array<types::global_dof_index, 3>> point_dofs;
      };
      SurfacePiece
      surface_piece() const;

    private:
      void
      build_mesh(const Triangulation<2, 3> &serial_mesh);
      void
      setup_dofs();
      void
      setup_edges();

      MPI_Comm  communicator;
      MeshSetup setup;
      // Destroyed in reverse order: the dofs before the mesh they live on.
      std::unique_ptr<parallel::fullydistributed::Triangulation<2, 3>> triangulation;
      std::unique_ptr<FESystem<2, 3>>                                  fe;
      std::unique_ptr<MappingFE<2, 3>>                                 mapping;
      std::unique_ptr<DoFHandler<2, 3>>                                dof_handler;
      IndexSet                                                         locally_owned_dofs;
      IndexSet                                           locally_relevant_dofs;
      VectorType                                         owned_prototype;   // zero
      VectorType                                         ghosted_prototype; // zero
      std::unique_ptr<const Epetra_Import>               ghost_import;
      IndexSet                                           displacement_dofs;
      unsigned int                                       vertex_count = 0;
      std::vector<std::pair<unsigned int, unsigned int>> dof_vertex_component;
      std::vector<Element>                               element_table;
      std::vector<Edge>                                  edge_table;
      std::vector<types::global_dof_index>               unused;
    };
  } // namespace mesh
} // namespace clothsim
