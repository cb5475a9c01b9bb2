#pragma once

// The elimination tree of a sparse symmetric matrix and a postorder of it, the skeleton
// of a sparse Cholesky factorisation (Liu, "The role of elimination trees in sparse
// factorization", SIAM J. Matrix Anal. Appl. 11, 1990).

#include <vector>

namespace clothsim
{
  // Liu's elimination tree of the lower pattern given by rows: for each row i, the
  // columns j < i of its entries (ibid., algorithm 4.2). parent[j] is -1 for a root.
  std::vector<int>
  elimination_tree(const std::vector<std::vector<int>> &row_entries);

  // A postorder of the forest `parent` (children before parents, each subtree
  // contiguous, children in increasing order): post[p] is the node visited p-th.
  std::vector<int>
  postorder(const std::vector<int> &parent);
} // namespace clothsim
