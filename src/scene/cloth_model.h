#pragma once

// The discrete cloth: a distributed triangle mesh, the displacement unknowns on it, the
// pinned vertices, and the incremental potential of one step assembled from the element
// kernels.
//
// Unknowns: displacement u = x - X of every vertex (FE_SimplexP(1)^3) and, when the scene
// has bending, one director angle ψ per edge (physics/bending.h): a fourth component
// FE_SimplexP(2) whose vertex dofs are constrained to zero, which leaves exactly its one
// dof per edge. The FESystem's local dofs are mapped to (vertex, component) and (edge)
// once at set-up. Every edge keeps a reference vector r_E (its director at ψ = 0);
// after each converged step the model re-bases r_E on the current director and sets ψ to
// zero, so the angles stay small. Clamped edges keep ψ = 0 and their rest director.
//
// Incremental potential of a step (Gast & Schroeder 2014; backward Euler when w_i =
// 1/dt²):
//   Φ(u) = w_i/2 (u - û)ᵀ M (u - û) + W(u) - λ (f_g + f_ext)ᵀ u
//          + w_d/2 (u - u_n)ᵀ (α M + β K_n) (u - u_n)
// with M the mass matrix (none on ψ), W the membrane plus bending energy, f_g the gravity
// load, f_ext the point and line forces, λ the load factor, K_n the projected membrane
// tangent at the step's start. Its gradient is the residual
// and its Hessian the tangent; all terms are sums over triangles, so one cell loop
// assembles them.

#include <boost/serialization/array.hpp>
#include <boost/serialization/string.hpp>
#include <deal.II/base/function_parser.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include "io/parameters.h"
#include "mesh/gmsh_reader.h"
#include "physics/bending.h"
#include "physics/membrane.h"
#include "physics/pressure.h"
#include "scene/spring_network.h"
#include "solvers/linear_solver.h"

#include <array>
#include <memory>
#include <vector>

namespace clothsim
{
  using VectorType = TrilinosWrappers::MPI::Vector;
  using MatrixType = TrilinosWrappers::SparseMatrix;

  // Coefficients of one step's incremental potential (see the file comment).
  struct StepTerms
  {
    double            inertia_weight    = 0.;      // w_i, 1/s²
    double            damping_weight    = 0.;      // w_d, 1/s
    double            load_factor       = 1.;      // λ
    const VectorType *predictor         = nullptr; // û (ghosted); needed if w_i > 0
    const VectorType *previous          = nullptr; // u_n (ghosted); needed if w_d > 0
    bool              projected_tangent = true;    // Hessian: projected (PSD) or exact
  };

  struct Energies
  {
    double kinetic   = 0.; // J
    double elastic   = 0.; // J
    double potential = 0.; // J, gravity: -f_gᵀ u (zero in the reference configuration)
  };

  // A probe snapped to the nearest mesh vertex.
  struct ProbeLocation
  {
    std::string                            name;
    Point<3>                               reference_point; // the vertex, m
    std::array<types::global_dof_index, 3> dofs;            // x, y, z displacement dofs

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &name &reference_point &dofs;
    }
  };

  class ClothModel
  {
  public:
    // Builds the distributed mesh from `serial_mesh` (the same on every rank),
    // distributes dofs, resolves pinned groups. Throws InputError (naming
    // `parameter_file`) for unknown groups.
    ClothModel(const MPI_Comm             communicator,
               const Parameters          &parameters,
               const std::string         &parameter_file,
               const Triangulation<2, 3> &serial_mesh,
               const mesh::MeshGroups    &groups);

    const DoFHandler<2, 3> &
    get_dof_handler() const
    {
      return dof_handler;
    }
    const MappingFE<2, 3> &
    get_mapping() const
    {
      return mapping;
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
    MPI_Comm
    get_communicator() const
    {
      return communicator;
    }
    // Homogeneous constraints on the pinned dofs (Newton updates there are zero).
    const AffineConstraints<double> &
    get_constraints() const
    {
      return constraints;
    }
    types::global_dof_index
    n_dofs() const
    {
      return dof_handler.n_dofs();
    }
    unsigned int
    n_vertices() const
    {
      return vertex_count;
    }
    // The shell's bending unknowns (director angles) exist: FEM with Material/Bending.
    bool
    has_bending() const
    {
      return parameters.material.bending && !uses_springs();
    }
    // Model = mass-spring: springs replace the membrane and bending elements.
    bool
    uses_springs() const
    {
      return parameters.scene.model == Model::mass_spring;
    }
    // The springs (only with uses_springs()).
    const SpringNetwork &
    get_springs() const
    {
      Assert(springs != nullptr, ExcInternalError());
      return *springs;
    }
    // Names of the solution's components for output: displacement (3), director angle.
    std::vector<std::string>
    component_names(const std::string &displacement_name) const;
    unsigned int
    n_pinned_dofs() const;

    // Vectors and matrix with this model's layout.
    void
    initialize_owned(VectorType &vector) const;
    void
    initialize_ghosted(VectorType &vector) const;
    void
    initialize_matrix(MatrixType &matrix) const;

    // The state at t = 0 (owned vectors): 'Time/Initial displacement' and 'Initial
    // velocity' at every vertex (angles zero), pinned dofs at their prescribed position
    // (velocity as given).
    void
    initial_state(VectorType &u, VectorType &v) const;

    // Sets the pinned entries of `u` (owned) to the prescribed displacement at time t.
    void
    apply_pinned_displacement(const double time, VectorType &u) const;

    // After a converged step: every unclamped edge's reference vector becomes its current
    // director (from `u_ghosted`), and the angles in `u` (owned) become zero. A no-op
    // without bending. (Angle rates stay: relative to the new references they still
    // predict the next step's rotation.)
    void
    rebase_directors(const VectorType &u_ghosted, VectorType &u);

    // Per-cell tangent K_n at the step's start for stiffness-proportional damping (no-op
    // if β=0).
    void
    prepare_damping(const VectorType &u_n);

    // Φ(u) of the step (returned, summed over ranks); if non-null, its gradient (owned
    // vector, zero at pinned dofs) and Hessian (with the pinned rows/columns eliminated).
    double
    assemble(const VectorType &u,
             const StepTerms  &terms,
             VectorType       *gradient,
             MatrixType       *hessian) const;

    // Internal (elastic) forces ∇W(u) on every dof, pinned ones included (owned vector):
    // at pinned dofs these are the reactions the pins exert, with opposite sign.
    void
    internal_forces(const VectorType &u, VectorType &forces) const;

    // Energies at displacement u and velocity v (ghosted), summed over ranks.
    Energies
    energies(const VectorType &u, const VectorType &v) const;

    // Smallest and largest current/reference area ratio over all triangles (collapse and
    // blow-up detection); a NaN gives (-1, infinity).
    std::pair<double, double>
    area_ratio_range(const VectorType &u) const;

    // The lumped mass of every dof's vertex (owned vector, kg; zero on angle dofs).
    void
    lumped_masses(VectorType &masses) const;

    // Provot's strain limit after a dynamic step (mass-spring only): Gauss–Seidel sweeps
    // over the structural springs, colour by colour (at most 'Strain limit iterations'),
    // each shortening the springs stretched beyond the limit, and move/dt added to the
    // velocities. `u`, `v` owned. Returns the number of springs still beyond the limit (0
    // when it converged) and, in `largest_strain`, the largest |strain| among them.
    types::global_dof_index
    limit_strain(VectorType  &u,
                 VectorType  &v,
                 const double dt,
                 double      &largest_strain) const;

    // Per locally owned cell (indexed by active_cell_index): Green strain and stress
    // norms.
    void
    cell_strain_stress(const VectorType &u,
                       Vector<double>   &strain,
                       Vector<double>   &stress) const;

    // Per locally owned cell: the strain (l - L)/L of its edge with the largest |strain|
    // (the structural springs' strain in the mass-spring model).
    void
    cell_edge_strain(const VectorType &u, Vector<double> &strain) const;

    // Per locally owned cell: norm of the curvature change |Ā⁻¹(b - B̄)| (1/m); zero
    // without bending.
    void
    cell_curvature_change(const VectorType &u, Vector<double> &curvature) const;

    // Snaps each probe to the nearest vertex (the same on every rank).
    std::vector<ProbeLocation>
    locate_probes(const std::vector<Probe> &probes) const;

    // Every vertex's reference position and displacement (X, Y, Z, ux, uy, uz) from `u`
    // (ghosted), sorted by reference position, on rank 0 (empty elsewhere).
    std::vector<std::array<double, 6>>
    vertex_displacements(const VectorType &u) const;

    // Values of the given dofs of `u` (ghosted) on every rank.
    std::vector<double>
    gather_values(const VectorType                           &u,
                  const std::vector<types::global_dof_index> &dofs) const;

    // AMG near-null space on the locally owned dofs: translations (and the in-plane
    // rotation of a nearly planar sheet) on the displacements, zero on the angles.
    NearNullSpace
    near_null_space() const;

    double
    total_mass() const; // kg
    double
    reference_area() const; // m²

  private:
    // Everything the cell loop needs about one locally owned triangle, precomputed.
    struct Element
    {
      std::array<types::global_dof_index, 9> dofs; // (vertex v, component c) at 3v + c
      std::array<int, 9>                     local_dofs; // in ghosted vectors
      physics::TrianglePositions             reference;
      physics::MembraneRestData              rest;
      // With bending: edge i (opposite vertex i): its angle dof, its slot in `edges`,
      // the sign s_i.
      std::array<types::global_dof_index, 3> angle_dofs;
      std::array<unsigned int, 3>            edge_slots;
      std::array<double, 3>                  edge_signs;
      physics::BendingRestData               bending_rest;
    };

    // One edge of a locally owned triangle, with its end points in global order (the
    // lexicographic order of their reference positions, the same on every rank).
    struct Edge
    {
      types::global_dof_index                               angle_dof;
      std::array<std::array<types::global_dof_index, 3>, 2> vertex_dofs;
      std::array<Point<3>, 2>                               reference_points;
      Tensor<1, 3>                                          reference; // r_E
      bool                                                  clamped = false;
    };

    void
    build_mesh(const Triangulation<2, 3> &serial_mesh);
    void
    setup_dofs();
    void
    setup_edges();
    void
    resolve_pinned(const std::string &parameter_file, const mesh::MeshGroups &groups);
    void
    resolve_loads(const std::string &parameter_file, const mesh::MeshGroups &groups);

    // Parses 'fx; fy; fz' into `function`; InputError naming `entry` if it fails.
    static void
    parse_vector_function(FunctionParser<3> &function,
                          const std::string &expressions,
                          const bool         time_dependent,
                          const std::string &parameter_file,
                          const std::string &entry);

    // f_extᵀ u over the locally owned dofs (J; zero without point and line forces).
    double
    local_external_work(const VectorType &u) const;

    // The element's edge directors (reference vectors, signs) and angles ψ from `u`.
    physics::EdgeDirectors
    edge_directors(const Element       &element,
                   const VectorType    &u,
                   physics::EdgeAngles &psi) const;

    // Current vertex positions x = X + u of an element; u_e gets its displacements.
    physics::TrianglePositions
    current_positions(const Element         &element,
                      const VectorType      &u,
                      std::array<double, 9> &u_e) const;

    // The element's 9 displacement values from a ghosted vector.
    // Calls function(active cell index, element, current positions) for every locally
    // owned cell.
    template <class CellFunction>
    void
    for_each_owned_cell(const VectorType &u, const CellFunction &function) const;

    void
    gather(const VectorType      &ghosted,
           const Element         &element,
           std::array<double, 9> &values) const;

    MPI_Comm                                        communicator;
    const Parameters                               &parameters;
    parallel::fullydistributed::Triangulation<2, 3> triangulation;
    std::unique_ptr<FESystem<2, 3>>                 fe;
    MappingFE<2, 3>                                 mapping;
    DoFHandler<2, 3>                                dof_handler;
    IndexSet                                        locally_owned_dofs;
    IndexSet                                        locally_relevant_dofs;
    AffineConstraints<double>                       constraints;

    // local dof i of a cell -> (vertex, component), from the FESystem.
    std::vector<std::pair<unsigned int, unsigned int>> local_dof_vertex_component;

    std::vector<Element>      elements;
    physics::MembraneMaterial material;
    physics::BendingMaterial  bending_material;
    std::vector<Edge>         edges;
    unsigned int              vertex_count = 0;
    // Constrained-to-zero dofs that no element uses (the P2 vertex dofs of the angle
    // component), owned here: the tangent gets a unit diagonal there.
    std::vector<types::global_dof_index> unused_dofs;
    // Point and line forces f_ext (owned, zero at pinned dofs), N.
    VectorType external_forces;
    // Apex of the pressure potential's cones: the reference surface's centroid.
    Point<3> pressure_apex;

    // Pinned dofs (locally relevant): dof, component, reference position of its vertex.
    struct PinnedDof
    {
      types::global_dof_index dof;
      unsigned int            component;
      Point<3>                reference;
    };
    std::vector<PinnedDof>              pinned;
    mutable FunctionParser<3>           pinned_displacement;
    FunctionParser<3>                   initial_displacement_function;
    FunctionParser<3>                   initial_velocity_function;
    std::vector<physics::ElementMatrix> damping_tangents; // per element, if β > 0
    std::unique_ptr<SpringNetwork>      springs;          // Model = mass-spring
    // Inverse lumped masses (ghosted, 0 on pinned dofs), for the strain limit.
    VectorType inverse_masses;
  };
} // namespace clothsim
