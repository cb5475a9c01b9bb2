#include "solvers/supernodal_cholesky.h"

#include "solvers/blas_kernels.h"
#include "solvers/dense_kernels.h"
#include "solvers/elimination_tree.h"
#include "solvers/flush_denormals.h"
#include "solvers/panel_cholesky.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <type_traits>

namespace clothsim
{
  namespace
  {
    // Relaxed amalgamation: merge a child supernode of `columns` columns into its
    // parent if the merged one has at most 4 columns, or its explicit zeros stay
    // below a fraction that falls with its size (CHOLMOD's defaults).
    bool
    amalgamate(const int columns, const double zero_fraction)
    {
      return columns <= 4 || (columns <= 16 && zero_fraction < 0.8) ||
             (columns <= 48 && zero_fraction < 0.1) || zero_fraction < 0.05;
    }
  } // namespace


  SupernodalCholesky::SupernodalCholesky(const bool single_precision,
                                         const bool blas_panels)
    : single(single_precision)
    , written_out_panels(!blas_panels && dense::panel_kernel_available())
    , square_updates(avx512_blas_kernels())
  {}


  void
  SupernodalCholesky::analyse(const int               n_rows,
                              const std::vector<int> &rows,
                              const std::vector<int> &columns,
                              const std::vector<int> &order,
                              const std::vector<int> &value_index,
                              const int               schur_size)
  {
    n       = n_rows;
    n_schur = schur_size;
    if (static_cast<int>(order.size()) != n || rows.size() != columns.size() ||
        (!value_index.empty() && value_index.size() != rows.size()) || n_schur < 0 ||
        n_schur > n)
      throw std::invalid_argument("SupernodalCholesky::analyse: sizes differ");
    std::vector<int> position(n, -1);
    for (int p = 0; p < n; ++p)
      {
        if (order[p] < 0 || order[p] >= n || position[order[p]] != -1)
          throw std::invalid_argument("SupernodalCholesky::analyse: not a permutation");
        position[order[p]] = p;
      }

    // The lower pattern in elimination order, by rows; then the same in the order of
    // a postorder of its elimination tree (children before parents, subtrees
    // contiguous), which is the final permutation. The Schur block's rows are joined
    // in a chain (each to the next in the order), which makes them a path at the top
    // of the tree: the postorder keeps them last, in their order.
    const auto rows_of = [&](const std::vector<int> &where) {
      std::vector<std::vector<int>> row_entries(n);
      const auto                    add = [&](const int a, const int b) {
        if (a != b)
          row_entries[std::max(a, b)].push_back(std::min(a, b));
      };
      for (std::size_t k = 0; k < rows.size(); ++k)
        add(where[rows[k]], where[columns[k]]);
      for (int p = n - n_schur + 1; p < n; ++p)
        add(where[order[p - 1]], where[order[p]]);
      return row_entries;
    };
    {
      const std::vector<int> post = postorder(elimination_tree(rows_of(position)));
      std::vector<int>       relabel(n);
      for (int p = 0; p < n; ++p)
        relabel[post[p]] = p;
      permutation.resize(n);
      for (int i = 0; i < n; ++i)
        permutation[i] = relabel[position[i]];
      for (int p = n - n_schur; p < n; ++p)
        if (permutation[order[p]] != p)
          throw std::logic_error("SupernodalCholesky::analyse: Schur block moved");
    }
    const std::vector<std::vector<int>> row_entries = rows_of(permutation);
    const std::vector<int>              parent      = elimination_tree(row_entries);
    std::vector<std::vector<int>>       column_entries(n);
    for (int i = 0; i < n; ++i)
      for (int j : row_entries[i])
        column_entries[j].push_back(i);

    // Column structures of L (rows below the diagonal): A's column joined with each
    // child's structure less the child itself. A fundamental supernode is a chain j,
    // j + 1, ... in which each column is its successor's only child and its structure
    // is the successor's plus the successor: only the chain's first column keeps its
    // structure, and column c's is the entries of its chain's first beyond c.
    std::vector<std::vector<int>> first_structure;
    std::vector<int>              chain_of(n), chain_first, n_kids(n, 0), marker(n, -1);
    std::vector<std::int64_t>     count(n);
    std::vector<int>              head(n, -1), next(n, -1);
    for (int j = n - 1; j >= 0; --j)
      if (parent[j] != -1)
        {
          ++n_kids[parent[j]];
          next[j]         = head[parent[j]];
          head[parent[j]] = j;
        }
    std::vector<int> s;
    for (int j = 0; j < n; ++j)
      {
        s.clear();
        marker[j] = j;
        for (int i : column_entries[j])
          if (marker[i] != j)
            {
              marker[i] = j;
              s.push_back(i);
            }
        for (int c = head[j]; c != -1; c = next[c])
          {
            const std::vector<int> &chain = first_structure[chain_of[c]];
            for (auto i = std::upper_bound(chain.begin(), chain.end(), c);
                 i != chain.end();
                 ++i)
              if (marker[*i] != j)
                {
                  marker[*i] = j;
                  s.push_back(*i);
                }
          }
        count[j] = static_cast<std::int64_t>(s.size()) + 1;
        // The Schur block is one supernode (one dense front), of no other column.
        if (j > n - n_schur || (j > 0 && j != n - n_schur && parent[j - 1] == j &&
                                n_kids[j] == 1 && count[j - 1] == count[j] + 1))
          chain_of[j] = chain_of[j - 1];
        else
          {
            chain_of[j] = static_cast<int>(chain_first.size());
            chain_first.push_back(j);
            std::sort(s.begin(), s.end());
            first_structure.push_back(s);
          }
      }
    const int n_chains = static_cast<int>(chain_first.size());
    chain_first.push_back(n);

    // Relaxed amalgamation, children before parents: a chain absorbs the supernode
    // that ends just before it (its last child in the postorder) while the merged
    // supernode's explicit zeros stay small. The merged rows below are the parent's:
    // a child's structure lies within its parent's columns and rows.
    std::vector<int>          merged_into(n_chains, -1), begin(n_chains);
    std::vector<std::int64_t> true_entries(n_chains, 0);
    const auto                representative = [&](int c) {
      while (merged_into[c] != -1)
        c = merged_into[c];
      return c;
    };
    for (int c = 0; c < n_chains; ++c)
      {
        begin[c] = chain_first[c];
        for (int j = chain_first[c]; j < chain_first[c + 1]; ++j)
          true_entries[c] += count[j];
      }
    for (int p = 0; p < n_chains - (n_schur > 0 ? 1 : 0); ++p)
      while (begin[p] > 0)
        {
          const int child = representative(chain_of[begin[p] - 1]);
          const int last  = chain_first[child + 1] - 1; // the child's last column
          if (parent[last] != begin[p])
            break; // begin[p] has no children
          const std::int64_t k = chain_first[p + 1] - begin[child];
          const std::int64_t r = static_cast<std::int64_t>(first_structure[p].size()) -
                                 (chain_first[p + 1] - chain_first[p] - 1);
          const std::int64_t stored = k * (k + 1) / 2 + k * r;
          const double       zeros =
            static_cast<double>(stored - true_entries[p] - true_entries[child]) / stored;
          if (!amalgamate(static_cast<int>(k), zeros))
            break;
          merged_into[child] = p;
          true_entries[p] += true_entries[child];
          begin[p] = begin[child];
        }
    // (chain_first[c + 1] - 1 is c's last column only while c is unmerged, which is
    // the case above: a child is merged once, into the chain after it.)

    // The supernodes: unmerged chains, in order of their columns.
    first_column.clear();
    below_start.assign(1, 0);
    below_rows.clear();
    std::vector<int> supernode_of(n);
    for (int c = 0; c < n_chains; ++c)
      if (merged_into[c] == -1)
        {
          const int s = static_cast<int>(first_column.size());
          first_column.push_back(begin[c]);
          for (int j = begin[c]; j < chain_first[c + 1]; ++j)
            supernode_of[j] = s;
          const std::vector<int> &chain = first_structure[c];
          for (auto i =
                 std::upper_bound(chain.begin(), chain.end(), chain_first[c + 1] - 1);
               i != chain.end();
               ++i)
            below_rows.push_back(*i);
          below_start.push_back(static_cast<int>(below_rows.size()));
        }
    const int n_nodes = static_cast<int>(first_column.size());
    first_column.push_back(n);
    first_structure.clear();

    // Where a row of supernode s's front is: its columns first, then its rows below.
    const auto local_row = [&](const int s, const int row) {
      if (row < first_column[s + 1])
        return row - first_column[s];
      const auto b = below_rows.begin() + below_start[s],
                 e = below_rows.begin() + below_start[s + 1];
      return static_cast<int>(std::lower_bound(b, e, row) - b) +
             (first_column[s + 1] - first_column[s]);
    };
    const auto front_size = [&](const int s) {
      return first_column[s + 1] - first_column[s] + below_start[s + 1] - below_start[s];
    };

    // Each matrix entry's place in its front (column-major, m x m).
    std::vector<int> entry_count(n_nodes + 1, 0);
    std::vector<int> entry_node(rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k)
      {
        const int a = permutation[rows[k]], b = permutation[columns[k]];
        entry_node[k] = supernode_of[std::min(a, b)];
        ++entry_count[entry_node[k] + 1];
      }
    std::partial_sum(entry_count.begin(), entry_count.end(), entry_count.begin());
    entry_start = entry_count;
    entry_index.resize(rows.size());
    entry_position.resize(rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k)
      {
        const int a = permutation[rows[k]], b = permutation[columns[k]];
        const int node     = entry_node[k];
        const int column   = std::min(a, b) - first_column[node];
        const int at       = entry_count[node]++;
        entry_index[at]    = value_index.empty() ? static_cast<int>(k) : value_index[k];
        entry_position[at] = local_row(node, std::max(a, b)) +
                             static_cast<std::int64_t>(column) * front_size(node);
      }

    // Each update row's place in the parent's front; the factor's storage; the
    // largest front and the deepest stack of waiting updates.
    std::vector<int> n_children(n_nodes + 1, 0);
    for (int s = 0; s < n_nodes; ++s)
      if (below_start[s + 1] > below_start[s])
        ++n_children[supernode_of[below_rows[below_start[s]]] + 1];
    std::partial_sum(n_children.begin(), n_children.end(), n_children.begin());
    child_start = n_children;
    child_list.resize(child_start.back());
    for (int s = 0; s < n_nodes; ++s)
      if (below_start[s + 1] > below_start[s])
        child_list[n_children[supernode_of[below_rows[below_start[s]]]]++] = s;
    parent_map_start.assign(1, 0);
    parent_map.clear();
    factor_start.assign(1, 0);
    // Two stacks of waiting updates: a supernode's update goes on the stack of its
    // depth's parity, where it is assembled and computed in place, and its children's
    // are read from the other one. Each stack stays last in, first out (in the
    // postorder, a node's subtree has consumed everything it pushed but the node's
    // children's updates), and no update is copied.
    parity.assign(n_nodes, 0);
    for (int s = n_nodes - 1; s >= 0; --s)
      if (below_start[s + 1] > below_start[s])
        parity[s] = 1 - parity[supernode_of[below_rows[below_start[s]]]];
    std::int64_t largest = 0, stack[2] = {0, 0};
    max_stack[0] = max_stack[1] = 0;
    n_operations                = 0.;
    std::vector<std::int64_t> pushed[2];
    for (int s = 0; s < n_nodes; ++s)
      {
        const std::int64_t k = first_column[s + 1] - first_column[s],
                           r = below_start[s + 1] - below_start[s], m = k + r;
        largest = std::max(largest, m);
        factor_start.push_back(factor_start.back() + m * k);
        if (n_schur == 0 || s + 1 < n_nodes)
          n_operations += k * k * k / 3. + k * k * r + k * r * r;
        const int side = parity[s];
        for (int c = child_start[s]; c < child_start[s + 1]; ++c)
          {
            stack[1 - side] -= pushed[1 - side].back();
            pushed[1 - side].pop_back();
          }
        if (r > 0)
          {
            const int p = supernode_of[below_rows[below_start[s]]];
            for (int i = below_start[s]; i < below_start[s + 1]; ++i)
              parent_map.push_back(local_row(p, below_rows[i]));
            pushed[side].push_back(r * r);
            stack[side] += r * r;
            max_stack[side] = std::max(max_stack[side], stack[side]);
          }
        parent_map_start.push_back(static_cast<int>(parent_map.size()));
      }
    n_factor_entries = factor_start.back();
    largest_front    = largest;
    // The numeric arrays come with the first factorisation: a candidate analysed only
    // for its operation count (prefer_vertex_order) never touches their pages.
    in_single = {};
    in_double = {};
  }


  template <typename Number>
  void
  SupernodalCholesky::allocate(Numeric<Number> &numeric) const
  {
    if (numeric.rhs.size() == static_cast<std::size_t>(n))
      return;
    numeric.factor.assign(n_factor_entries, 0);
    numeric.stacks[0].assign(max_stack[0], 0);
    numeric.stacks[1].assign(max_stack[1], 0);
    numeric.work.assign(largest_front, 0);
    numeric.rhs.assign(n, 0);
  }


  bool
  SupernodalCholesky::factorize(const double *values, const double *rhs)
  {
    const FlushDenormals flush;
    forwarded = false;
    const bool ok =
      single ? factorize(in_single, values, rhs) : factorize(in_double, values, rhs);
    forwarded = ok && rhs != nullptr;
    return ok;
  }


  void
  SupernodalCholesky::solve(double *x, const std::function<void(double *)> &schur_solve)
  {
    if (n_schur > 0 && !schur_solve)
      throw std::invalid_argument("SupernodalCholesky::solve: the Schur block's solve");
    const FlushDenormals flush;
    forwarded = false; // numeric.rhs is overwritten
    if (single)
      solve(in_single, x, schur_solve, false);
    else
      solve(in_double, x, schur_solve, false);
  }


  void
  SupernodalCholesky::finish_solve(double                              *x,
                                   const std::function<void(double *)> &schur_solve)
  {
    if (!forwarded)
      throw std::logic_error("SupernodalCholesky::finish_solve: the last factorize() "
                             "had no right-hand side, or its solve was finished");
    if (n_schur > 0 && !schur_solve)
      throw std::invalid_argument(
        "SupernodalCholesky::finish_solve: the Schur block's solve");
    forwarded = false;
    const FlushDenormals flush;
    if (single)
      solve(in_single, x, schur_solve, true);
    else
      solve(in_double, x, schur_solve, true);
  }


  void
  SupernodalCholesky::add_schur_complement(double *schur) const
  {
    const auto add = [&](const auto &numeric) {
      const auto *front = numeric.factor.data() + factor_start[n_supernodes() - 1];
      for (std::int64_t j = 0; j < n_schur; ++j)
        for (std::int64_t i = j; i < n_schur; ++i)
          schur[i + j * n_schur] += front[i + j * n_schur];
    };
    if (n_schur == 0)
      return;
    if (single)
      add(in_single);
    else
      add(in_double);
  }


  template <typename Number>
  bool
  SupernodalCholesky::factorize(Numeric<Number> &numeric,
                                const double    *values,
                                const double    *rhs)
  {
    allocate(numeric);
    const int n_nodes = n_supernodes();
    if (rhs != nullptr)
      for (int i = 0; i < n; ++i)
        numeric.rhs[permutation[i]] = static_cast<Number>(rhs[i]);
    std::int64_t top[2] = {0, 0}; // ends of the update stacks
    for (int s = 0; s < n_nodes; ++s)
      {
        const int k = first_column[s + 1] - first_column[s],
                  r = below_start[s + 1] - below_start[s], m = k + r;
        // The front: its first k columns (m x k) in place in the factor, the rest
        // (r x r, the update for the parent) in place on its stack; lower triangles.
        const int side = parity[s];
        Number   *P    = numeric.factor.data() + factor_start[s];
        Number   *U    = numeric.stacks[side].data() + top[side];
        // Zeroed in one call where that is cheaper than a call per column: the whole
        // m x k panel (its upper triangle is never read), and a small update's whole
        // r x r square (a large one's lower triangle only, half the bytes). Against a
        // call per column, 3 % less time per factorisation (swinging sheet, N = 81).
        // An update computed on its whole square is zeroed whole too.
        const bool square = square_updates && r <= square_update_rows;
        std::fill(P, P + static_cast<std::int64_t>(m) * k, Number(0));
        if (r <= 64 || square)
          std::fill(U, U + static_cast<std::int64_t>(r) * r, Number(0));
        else
          for (int j = 0; j < r; ++j)
            std::fill(U + static_cast<std::int64_t>(j) * r + j,
                      U + static_cast<std::int64_t>(j + 1) * r,
                      Number(0));
        for (int e = entry_start[s]; e < entry_start[s + 1]; ++e)
          P[entry_position[e]] += static_cast<Number>(values[entry_index[e]]);
        // The children's updates are the top of the other stack, in the children's
        // order.
        std::int64_t from = top[1 - side];
        for (int c = child_start[s]; c < child_start[s + 1]; ++c)
          {
            const std::int64_t rc =
              below_start[child_list[c] + 1] - below_start[child_list[c]];
            from -= rc * rc;
          }
        top[1 - side] = from;
        for (int c = child_start[s]; c < child_start[s + 1]; ++c)
          {
            const int     child = child_list[c];
            const int    *map   = parent_map.data() + parent_map_start[child];
            const int     rc    = parent_map_start[child + 1] - parent_map_start[child];
            const Number *V     = numeric.stacks[1 - side].data() + from;
            int           jj    = 0;
            for (; jj < rc && map[jj] < k; ++jj)
              {
                Number       *column = P + static_cast<std::int64_t>(map[jj]) * m;
                const Number *v      = V + static_cast<std::int64_t>(jj) * rc;
                for (int ii = jj; ii < rc; ++ii)
                  column[map[ii]] += v[ii];
              }
            for (; jj < rc; ++jj)
              {
                Number       *column = U + static_cast<std::int64_t>(map[jj] - k) * r - k;
                const Number *v      = V + static_cast<std::int64_t>(jj) * rc;
                for (int ii = jj; ii < rc; ++ii)
                  column[map[ii]] += v[ii];
              }
            from += static_cast<std::int64_t>(rc) * rc;
          }
        if (n_schur > 0 && s + 1 == n_nodes)
          break; // the Schur complement, left to the caller
        if (written_out_panels)
          {
            if (!dense::blocked_panel_cholesky(k, m, P, written_out_block_columns))
              return false;
          }
        else
          {
            if (!dense::cholesky(k, P, m))
              return false;
            if (r > 0)
              dense::right_solve_transposed(r, k, P, m, P + k, m);
          }
        // The forward substitution through the panel while it is in cache: the
        // right-hand side's rows of this front are final, its descendants come first.
        if (rhs != nullptr)
          substitute(numeric, s, true);
        if (r > 0)
          {
            if (square)
              dense::subtract_product(r, r, k, P + k, m, P + k, m, U, r);
            else
              dense::subtract_gram(r, k, P + k, m, U, r);
            top[side] += static_cast<std::int64_t>(r) * r;
          }
      }
    return true;
  }


  template <typename Number>
  typename SupernodalCholesky::template Front<Number>
  SupernodalCholesky::front(Numeric<Number> &numeric, const int s) const
  {
    const int k = first_column[s + 1] - first_column[s],
              r = below_start[s + 1] - below_start[s];
    return {k,
            r,
            k + r,
            numeric.factor.data() + factor_start[s],
            numeric.rhs.data() + first_column[s],
            below_rows.data() + below_start[s]};
  }


  template <typename Number>
  void
  SupernodalCholesky::substitute(Numeric<Number> &numeric,
                                 const int        s,
                                 const bool       forward) const
  {
    const Front<Number> f              = front(numeric, s);
    const auto [k, r, m, L, xs, below] = f;
    Number *rhs = numeric.rhs.data(), *work = numeric.work.data();
    if (written_out_panels)
      {
        f.gather(rhs, work);
        if (forward)
          dense::panel_forward_solve(k, m, L, work);
        else
          dense::panel_backward_solve(k, m, L, work);
        std::copy(work, work + k, xs);
        for (int i = 0; forward && i < r; ++i)
          rhs[below[i]] = work[k + i];
        return;
      }
    if (forward)
      {
        dense::triangular_solve("N", k, L, m, xs);
        if (r > 0)
          {
            dense::multiply("N", r, k, Number(1), L + k, m, xs, Number(0), work);
            for (int i = 0; i < r; ++i)
              rhs[below[i]] -= work[i];
          }
        return;
      }
    if (r > 0)
      {
        for (int i = 0; i < r; ++i)
          work[i] = rhs[below[i]];
        dense::multiply("T", r, k, Number(-1), L + k, m, work, Number(1), xs);
      }
    dense::triangular_solve("T", k, L, m, xs);
  }


  template <typename Number>
  void
  SupernodalCholesky::solve(Numeric<Number>                     &numeric,
                            double                              *x,
                            const std::function<void(double *)> &schur_solve,
                            const bool                           forwarded)
  {
    // The supernodes eliminated here: all but the Schur block's.
    const int n_nodes = n_supernodes() - (n_schur > 0 ? 1 : 0);
    Number   *rhs     = numeric.rhs.data();
    if (!forwarded)
      {
        for (int i = 0; i < n; ++i)
          rhs[permutation[i]] = static_cast<Number>(x[i]);
        for (int s = 0; s < n_nodes; ++s)
          substitute(numeric, s, true);
      }
    if (n_schur > 0)
      {
        std::vector<double> block(rhs + n - n_schur, rhs + n);
        schur_solve(block.data());
        std::copy(block.begin(), block.end(), rhs + n - n_schur);
      }
    for (int s = n_nodes - 1; s >= 0; --s)
      substitute(numeric, s, false);
    for (int i = 0; i < n; ++i)
      x[i] = rhs[permutation[i]];
  }
} // namespace clothsim
