#pragma once

// The mass-spring model's springs on a distributed triangle mesh (Provot 1995), built
// from the same mesh, dofs and constraints as the finite elements:
//   structural: one spring on every mesh edge;
//   cross:      across every interior edge, between the two vertices opposite it (the
//               shear and bend springs of a triangle mesh: one spring, whose stiffness is
//               the shear plus the bend constant).
// Constants derived from the continuum (physics/mass_spring.h):
//   structural k_e = 8/(9(1-ν²)) E h Σ_T |T| / L_e²                        (exact energy
//              match on equilateral triangles at ν = 1/3, Van Gelder's weights elsewhere)
//   cross      k_b from the bending rigidity D, matching the hinge energy at the
//              reference fold angle θ_r; zero without Material/Bending. No shear part:
//              a triangle lattice's edges already resist shear, and a further
//              central-force lattice cannot change its Poisson ratio (1/3).
// or given directly (uniform, N/m). Each spring belongs to exactly one rank (the owner of
// the cell with the smaller CellId among the edge's two), so energies and forces are
// summed once under MPI.

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include "mesh/dealii_declarations.h"
#include "mesh/element_matrix_scatter.h"
#include "mesh/local_sums.h"
#include "physics/mass_spring.h"

#include <array>
#include <vector>

namespace clothsim
{
  using namespace dealii;

  // Where the spring constants come from.
  struct SpringConstants
  {
    // Derived from the continuum (true) or the uniform values below (false).
    bool   derived;
    double stretch_stiffness;    // k_m = E h, N/m (derived)
    double poisson_ratio;        // ν (derived)
    bool   bending;              // cross springs from the bending rigidity (derived)
    double bending_rigidity;     // D, N·m (derived)
    double bend_reference_angle; // θ_r, rad (derived)
    double structural_stiffness; // N/m (given)
    double cross_stiffness;      // N/m, shear + bend (given)
  };

  class SpringNetwork
  {
  public:
    using VectorType = TrilinosWrappers::MPI::Vector;
    using MatrixType = TrilinosWrappers::SparseMatrix;

    enum class Kind
    {
      structural,
      cross
    };

    struct Entry
    {
      Kind                                   kind;
      physics::Spring                        spring;
      std::array<types::global_dof_index, 6> dofs;       // end 0 x, y, z, end 1 x, y, z
      std::array<int, 6>                     local_dofs; // in ghosted vectors
      std::array<Point<3>, 2>                reference;
    };

    // `dof_handler` carries FE_SimplexP(1)^3 (displacements only); `ghosted_prototype`
    // is a ghosted vector of the model's layout (for local indices,
    // mesh/ghosted_values.h).
    SpringNetwork(const DoFHandler<2, 3> &dof_handler,
                  const SpringConstants  &constants,
                  const VectorType       &ghosted_prototype);

    const std::vector<Entry> &
    springs() const
    {
      return entries;
    }

    // Numbers of springs of each kind over all ranks.
    std::array<types::global_dof_index, 2>
    global_counts() const;

    // Smallest and largest stiffness of each kind over all ranks (N/m; 0 if none).
    std::array<std::pair<double, double>, 2>
    stiffness_range() const;

    // Couplings of the cross springs' ends (they share no cell).
    void
    add_sparsity(TrilinosWrappers::SparsityPattern &sparsity,
                 const AffineConstraints<double>   &constraints) const;

    // The springs' energy on this rank at displacement u (ghosted), J.
    double
    energy(const VectorType &u) const;

    // Adds the stiffness-proportional damping force c K_n v at the velocity v (ghosted;
    // K_n from prepare_damping) to `damping_force` (this rank's relevant dofs in the
    // order of ghosted vectors, physics/term.h). If `u` is non-null, the same loop
    // returns the springs' energy at u (else 0).
    double
    add_damping_force(const VectorType    &v,
                      const double         damping_coefficient,
                      std::vector<double> &damping_force,
                      const VectorType    *u = nullptr) const;

    // What add_to_step adds for each spring.
    struct StepParts
    {
      // The springs' energy ½ k (ℓ - L)²; `projected`: its Hessian drops the negative
      // transverse part.
      bool elastic   = true;
      bool projected = true;
      // Stiffness-proportional damping c/2 sᵀ K_n s with s = u - u_n (`previous`,
      // ghosted) and K_n from prepare_damping; off if c = 0.
      double            damping_coefficient = 0.;
      const VectorType *previous            = nullptr;
    };

    // Adds this rank's springs to a step's potential: value (returned), gradient and
    // Hessian (each may be null; distributed through `constraints`, not compressed).
    // Each spring's parts are summed into one local vector and matrix and distributed
    // once. If non-null, `damping_gradient` (this rank's relevant dofs in the order of
    // ghosted vectors, physics/term.h) also gets the damping's part of the gradient
    // alone, c K_n s.
    double
    add_to_step(const VectorType                &u,
                const StepParts                 &parts,
                const AffineConstraints<double> &constraints,
                VectorType                      *gradient,
                MatrixType                      *hessian,
                std::vector<double>             *damping_gradient = nullptr) const;

    // The springs' projected Hessians at u_n, for stiffness-proportional damping.
    void
    prepare_damping(const VectorType &u_n);

    // Number of colours of the structural springs: no two springs of one colour share a
    // vertex (greedy colouring in the order of the springs' reference positions, the
    // same for any number of ranks).
    unsigned int
    n_colors() const
    {
      return color_count;
    }

    // Provot's strain limit on the structural springs of one colour: adds each violating
    // spring's end moves to `moves` (owned, to be compressed with add; the springs of a
    // colour move disjoint vertices, so a sweep over the colours is a Gauss–Seidel
    // sweep). `inverse_mass` (ghosted): 0 on pinned dofs. A spring within 0.1 % of the
    // limit (strain below 1.001 limit) counts as satisfied. Returns the number of
    // violating springs on this rank; `largest_strain` is raised to the largest |strain|
    // among them.
    unsigned int
    add_strain_limit_moves(const VectorType  &u,
                           const VectorType  &inverse_mass,
                           const double       limit,
                           const bool         limit_compression,
                           const unsigned int color,
                           VectorType        &moves,
                           double            &largest_strain) const;

  private:
    SpringNetwork::Entry
    make_entry(const Kind                                    kind,
               const double                                  stiffness,
               const std::array<types::global_dof_index, 3> &dofs_0,
               const std::array<types::global_dof_index, 3> &dofs_1,
               const Point<3>                               &x_0,
               const Point<3>                               &x_1,
               const VectorType                             &ghosted_prototype) const;

    physics::SpringPositions
    current_positions(const Entry &entry, const VectorType &u) const;

    void
    color_structural_springs();

    MPI_Comm           communicator;
    unsigned int       n_relevant_dofs;
    std::vector<Entry> entries;
    // Per entry, if β > 0: the block B of the projected Hessian at u_n,
    // K_n = [[B, -B], [-B, B]] (physics/mass_spring.h).
    std::vector<Tensor<2, 3>>          damping_blocks;
    mutable mesh::LocalSums            gradient_sums;   // add_to_step's gradient
    mutable mesh::ElementMatrixScatter hessian_scatter; // and its Hessian
    std::vector<unsigned int>          colors;          // per entry (structural)
    unsigned int                       color_count = 0;
  };
} // namespace clothsim
