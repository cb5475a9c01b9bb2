#pragma once

// Sparse Cholesky factorisation A = P L Lᵀ Pᵀ in single or double precision, multifrontal
// and supernodal (Duff & Reid, ACM TOMS 9, 1983; Liu, SIAM Review 34, 1992), for a
// sequence of symmetric positive definite matrices that share one sparsity: a Newton
// run's tangents. Everything that depends only on the sparsity is computed once by
// analyse(): the elimination tree, the supernodes (relaxed amalgamation as in CHOLMOD:
// Chen, Davis, Hager & Rajamanickam, ACM TOMS 35, 2008), where each matrix entry lands in
// its front, and where each child's update lands in its parent's front. factorize() then
// runs only dense kernels (BLAS and LAPACK) and precomputed scatters: no searching,
// sorting or allocation, which is what a general-purpose solver spends most of its time
// on for the small fronts of a 2D mesh.

#include <cstdint>
#include <vector>

namespace clothsim
{
  class SupernodalCholesky
  {
  public:
    // The factors' precision (the matrix is given in double either way).
    explicit SupernodalCholesky(bool single_precision = true)
      : single(single_precision)
    {}

    // The pattern of the upper triangle (0-based, rows[k] <= columns[k], each entry
    // once), and the elimination order: order[p] is the row eliminated p-th (a
    // fill-reducing permutation, e.g. from MUMPS' analysis). Entry k's value will be
    // values[value_index[k]] in factorize() (values[k] if value_index is empty), e.g.
    // its position in a compressed-row matrix's value array that holds both triangles.
    void
    analyse(int                     n,
            const std::vector<int> &rows,
            const std::vector<int> &columns,
            const std::vector<int> &order,
            const std::vector<int> &value_index = {});

    // Factorises the matrix whose upper-triangle entries are in `values` (where
    // analyse() placed them). Returns false if a pivot is not positive (the matrix is not
    // positive definite, or too ill-conditioned for the factors' precision).
    bool
    factorize(const double *values);

    // x = A⁻¹ b in place, with the last factors.
    void
    solve(double *x);

    // Floating-point operations of one factorisation, and entries in the factor.
    double
    operations() const
    {
      return n_operations;
    }
    std::int64_t
    factor_entries() const
    {
      return n_factor_entries;
    }
    int
    n_supernodes() const
    {
      return static_cast<int>(first_column.size()) - 1;
    }

  private:
    int n = 0;
    // Supernode s holds the permuted columns first_column[s] .. first_column[s + 1] - 1;
    // its front's rows are those columns followed by below_rows[below_start[s] ..
    // below_start[s + 1] - 1] (permuted indices, increasing).
    std::vector<int>          first_column;
    std::vector<int>          below_start;
    std::vector<int>          below_rows;
    std::vector<int>          child_start; // s's children: child_list[child_start[s] ..]
    std::vector<int>          child_list;
    std::vector<int>          parent_map; // s's update rows in its parent's front
    std::vector<int>          parent_map_start;
    std::vector<std::int64_t> factor_start; // s's m x k panel in `factor`
    std::vector<int>          permutation;  // permuted index of each original row
    // Matrix entries, grouped by supernode: value index and position in the front.
    std::vector<int>          entry_start;
    std::vector<int>          entry_index;
    std::vector<std::int64_t> entry_position;

    // The numeric part in the factors' precision.
    template <typename Number>
    struct Numeric
    {
      std::vector<Number> factor;
      // Updates waiting for their parent, by the parity of their supernode's depth.
      std::vector<Number> stacks[2];
      std::vector<Number> work; // solve
      std::vector<Number> rhs;  // solve, permuted
    };
    template <typename Number>
    bool
    factorize(Numeric<Number> &numeric, const double *values);
    template <typename Number>
    void
    solve(Numeric<Number> &numeric, double *x);

    bool              single;
    Numeric<float>    in_single;
    Numeric<double>   in_double;
    double            n_operations     = 0.;
    std::int64_t      n_factor_entries = 0;
    std::int64_t      max_stack[2]     = {0, 0};
    std::vector<char> parity; // of each supernode's depth in the tree
  };
} // namespace clothsim
