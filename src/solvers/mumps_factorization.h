#pragma once

// LDLᵀ factorisation of a symmetric sparse matrix by MUMPS (Amestoy et al., SIAM J.
// Matrix Anal. Appl. 23, 2001), called directly. Amesos_Mumps always hands MUMPS the
// whole matrix as unsymmetric (SYM = 0, an LU factorisation): here MUMPS gets the upper
// triangle with SYM = 1 (Cholesky-like LDLᵀ without pivoting, for SPD matrices) or
// SYM = 2 (LDLᵀ with 1x1 and 2x2 pivots, any symmetric matrix), about half the work and
// memory of LU. The rows stay distributed as the matrix is (MUMPS' distributed assembled
// input); so does the right-hand side (ICNTL(20) = 10), and the solution comes back
// distributed as MUMPS' factors hold it (ICNTL(21) = 1), from where one import brings it
// to the matrix's rows: nothing is gathered on one rank (swinging sheet, N = 321, 2
// ranks: 0.165 s per solve against 0.183 s gathered on rank 0).

#include <deal.II/base/types.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>
#include <mpi.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace clothsim
{
  class SubdomainCholesky;
  class SupernodalCholesky;

  class MumpsFactorization
  {
  public:
    enum class Symmetry
    {
      positive_definite, // SYM = 1
      indefinite         // SYM = 2
    };

    // `ordering`: MUMPS' fill-reducing ordering, ICNTL(7) (0 AMD, 3 SCOTCH, 4 PORD,
    // 5 METIS, 7 automatic). Debian's MUMPS has no METIS and takes its default for 5
    // (PORD, its log says). On the swinging sheet's tangent at N = 81 (45,604 unknowns)
    // that order costs 3.1e8 operations; METIS_NodeND called by us on the same graph
    // 3.3e8 to 4.3e8 (its options varied); AMD and SCOTCH were slower too.
    // The factors' precision: double, or single refined in double by each solve().
    // Single-precision factors take less time (swinging sheet at N = 81: 42 against 52
    // ms; at N = 321 0.81 against 1.17 s) and half the memory.
    enum class Precision
    {
      double_precision,
      single_refined
    };

    // ICNTL(7) = 5 asks for METIS, which Debian's MUMPS replaces by PORD (see above).
    static constexpr int default_ordering = 5;

    MumpsFactorization(MPI_Comm  communicator,
                       Symmetry  symmetry,
                       int       ordering  = default_ordering,
                       Precision precision = Precision::double_precision);
    ~MumpsFactorization();
    MumpsFactorization(const MumpsFactorization &) = delete;
    MumpsFactorization &
    operator=(const MumpsFactorization &) = delete;

    // Factorises `matrix` (collective). The first call also analyses its sparsity, which
    // later calls must share. Returns false with failure() set if MUMPS fails (e.g. a
    // zero pivot, or a non-positive one with Symmetry::positive_definite). `rhs`: the
    // right-hand side of the next solve(), if known; where SupernodalCholesky factorises
    // (definite; on several ranks through SubdomainCholesky) its forward substitution is
    // then done with the factorisation (SupernodalCholesky::factorize), and the next
    // solve() of that same b (compared entry by entry) does only the backward one.
    bool
    factorize(const Epetra_CrsMatrix &matrix, const Epetra_Vector *rhs = nullptr);

    // The unknowns' vertices or edges on the mesh (NearNullSpace::mesh_dofs; kept by
    // reference), before the first factorize(). Where SupernodalCholesky factorises,
    // the analysis then also orders the mesh's vertices (vertex_nested_dissection_order,
    // UFACTOR = 500) and keeps whichever of that order and MUMPS' costs fewer
    // operations, if every row it factorises is on the mesh.
    void
    set_mesh_unknowns(
      const std::vector<dealii::types::global_dof_index>                &dofs,
      const std::vector<std::array<dealii::types::global_dof_index, 2>> &vertices)
    {
      mesh_dofs     = &dofs;
      mesh_vertices = &vertices;
    }

    // The next factorize() analyses the sparsity again (the matrix's changed).
    void
    reanalyse()
    {
      analysed = false;
    }

    // x = A⁻¹ b with the last factorisation (collective; b and x on the matrix's rows).
    // With single-precision factors and a `matrix` A (the one factorised, or one close
    // to it), refined until ‖b - A x‖ ≤ relative_tolerance ‖b‖ (at most 10 refinement
    // steps, else it fails); without a matrix, not refined.
    bool
    solve(const Epetra_Vector    &b,
          Epetra_Vector          &x,
          const Epetra_CrsMatrix *matrix             = nullptr,
          double                  relative_tolerance = 0.);

    // Refinement steps of the last solve() (0 with double-precision factors).
    unsigned int
    refinements() const
    {
      return last_refinements;
    }

    // Negative pivots of the last factorisation: with SYM = 2 the number of negative
    // eigenvalues (Sylvester's law of inertia).
    int
    negative_pivots() const;

    const std::string &
    failure() const
    {
      return last_failure;
    }

  private:
    bool
    call(int job, const char *phase);

    // One solve with the factors, no refinement.
    bool
    solve_once(const Epetra_Vector &b, Epetra_Vector &x);

    std::unique_ptr<Epetra_Vector> residual_work, correction_work; // refinement
    static constexpr unsigned int  max_refinements  = 10;
    unsigned int                   last_refinements = 0;

    MPI_Comm communicator;
    struct Instance; // MUMPS' DMUMPS_STRUC_C or SMUMPS_STRUC_C
    std::unique_ptr<Instance> instance;
    bool                      analysed = false;
    // On one rank, rows whose only entry is their diagonal (e.g. the unused vertex dofs
    // of the director angles' P2 field, a seventh of the swinging sheet's unknowns) are
    // solved here, x_i = b_i / a_ii, not by MUMPS: each would be a tree of its own in
    // MUMPS' assembly forest (N = 81: 11,083 nodes with them, 4,522 without), and every
    // node costs time in each factorisation and solve (N = 81: 42 against 47 ms per
    // factorisation, 9.4 against 11.3 ms per solve). The others ("kept") are numbered
    // 0, 1, ... across the ranks in their order, and MUMPS sees only those. On several
    // ranks MUMPS gets every row: its solve adds the contributions that other ranks send
    // in the order they arrive, and on the reduced matrix's mapping that order varied
    // from run to run (swing N = 21 on 2 ranks: 5 of 70 solves repeated on the same
    // factors differed in the last bits), which would break bitwise restarts.
    std::vector<int>            kept_rows, decoupled_rows; // local row indices
    std::vector<double>         decoupled_diagonal;        // a_ii, factorised last
    int                         n_kept               = 0;  // over all ranks
    int                         n_negative_decoupled = 0;  // over all ranks
    std::unique_ptr<Epetra_Map> kept_map; // this rank's kept rows, by their new index
    // The upper triangle of the kept rows, row by row: 1-based new indices (fixed by the
    // analysis) and the values of the matrix factorised last.
    std::vector<int>    rows, columns;
    std::vector<double> values;
    std::vector<bool>   upper; // by entry of the row views: handed to MUMPS
    // Right-hand side: the kept rows' 1-based new indices (IRHS_loc) and values.
    std::vector<int>    rhs_rows;
    std::vector<double> rhs_values;
    // The kept rows' entries of the right-hand side given to the last factorize(), while
    // the Cholesky holds its forward substitution (empty otherwise).
    std::vector<double> forwarded_rhs;

    // Numbers the kept rows, finds the entries for MUMPS (first factorisation).
    bool
    set_up_rows(const Epetra_CrsMatrix &matrix);
    // Solution as MUMPS distributes it (ISOL_loc, SOL_loc, fixed by the factorisation)
    // and the import from there to the kept rows, made again when ISOL_loc changes.
    std::vector<int>               solution_rows, mapped_rows;
    std::vector<double>            solution_values;
    std::unique_ptr<Epetra_Map>    solution_map;
    std::unique_ptr<Epetra_Import> from_solution;
    std::string                    last_failure;

    // On one rank and positive definite (SYM = 1): MUMPS orders and analyses, and the
    // factorisations (reading the matrix's value array in place) and solves, in the
    // factors' precision, are SupernodalCholesky's (swinging sheet, N = 81, single: 15
    // against 38 ms per factorisation, 1.5 against 4 to 7 ms per solve).
    std::unique_ptr<SupernodalCholesky> cholesky;
    void
    set_up_cholesky(const Epetra_CrsMatrix &matrix);
    const std::vector<dealii::types::global_dof_index> *mesh_dofs = nullptr;
    const std::vector<std::array<dealii::types::global_dof_index, 2>> *mesh_vertices =
      nullptr;

    // On several ranks and positive definite (SYM = 1), MUMPS is not called: the
    // factorisations and solves are SubdomainCholesky's (each rank's interior by its
    // own SupernodalCholesky, the ranks' interface by a dense Schur complement). False
    // with last_failure set if its analysis fails.
    std::unique_ptr<SubdomainCholesky> subdomains;
    bool
    set_up_subdomains(const Epetra_CrsMatrix &matrix);

    // On several ranks and indefinite, MUMPS gets every row; rank 0 orders them
    // (solvers/fill_reducing_order.h, order_on_rank_zero) and MUMPS' analysis takes that
    // order (ICNTL(7) = 1, PERM_IN: `host_order` on rank 0). False if the ordering fails.
    bool
                     order_on_host();
    int              requested_ordering;
    std::vector<int> host_order;
  };
} // namespace clothsim
