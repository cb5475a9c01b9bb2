#include "solvers/elimination_tree.h"

namespace clothsim
{
  std::vector<int>
  elimination_tree(const std::vector<std::vector<int>> &row_entries)
  {
    const int        n = static_cast<int>(row_entries.size());
    std::vector<int> parent(n, -1), ancestor(n, -1);
    for (int i = 0; i < n; ++i)
      for (int j : row_entries[i])
        for (int r = j; r != -1 && r != i;)
          {
            const int next = ancestor[r];
            ancestor[r]    = i;
            if (next == -1)
              parent[r] = i;
            r = next;
          }
    return parent;
  }


  std::vector<int>
  postorder(const std::vector<int> &parent)
  {
    const int        n = static_cast<int>(parent.size());
    std::vector<int> head(n, -1), next(n, -1), post, stack;
    for (int j = n - 1; j >= 0; --j) // children listed in increasing order
      if (parent[j] != -1)
        {
          next[j]         = head[parent[j]];
          head[parent[j]] = j;
        }
    post.reserve(n);
    for (int root = 0; root < n; ++root)
      {
        if (parent[root] != -1)
          continue;
        stack.push_back(root);
        while (!stack.empty())
          {
            const int j = stack.back();
            if (head[j] != -1)
              {
                const int child = head[j];
                head[j]         = next[child];
                stack.push_back(child);
              }
            else
              {
                post.push_back(j);
                stack.pop_back();
              }
          }
      }
    return post;
  }
} // namespace clothsim
