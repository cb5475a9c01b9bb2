#pragma once

// A bounding-volume hierarchy of axis-aligned boxes (the broad phase of contact): built
// once by median splits along the longest axis of the boxes' centres, queried with a
// box for every stored box that overlaps it. Build O(n log n); a query visits
// O(log n + k) nodes for k overlaps of small boxes.

#include <deal.II/base/point.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace clothsim::physics
{
  using namespace dealii;

  struct Box
  {
    Point<3> lower, upper;

    // The box around `points`, grown by `margin` on every side.
    template <typename Container>
    static Box
    around(const Container &points, const double margin = 0.)
    {
      Box box{points[0], points[0]};
      for (const auto &p : points)
        for (unsigned int d = 0; d < 3; ++d)
          {
            box.lower[d] = std::min(box.lower[d], p[d]);
            box.upper[d] = std::max(box.upper[d], p[d]);
          }
      for (unsigned int d = 0; d < 3; ++d)
        {
          box.lower[d] -= margin;
          box.upper[d] += margin;
        }
      return box;
    }

    // The distance from y to the box (0 inside).
    double
    distance(const Point<3> &y) const
    {
      double sum = 0.;
      for (unsigned int d = 0; d < 3; ++d)
        {
          const double out = std::max({lower[d] - y[d], y[d] - upper[d], 0.});
          sum += out * out;
        }
      return std::sqrt(sum);
    }

    // The smallest box around both.
    Box
    merged(const Box &other) const
    {
      Box box = *this;
      for (unsigned int d = 0; d < 3; ++d)
        {
          box.lower[d] = std::min(lower[d], other.lower[d]);
          box.upper[d] = std::max(upper[d], other.upper[d]);
        }
      return box;
    }

    bool
    overlaps(const Box &other) const
    {
      for (unsigned int d = 0; d < 3; ++d)
        if (lower[d] > other.upper[d] || other.lower[d] > upper[d])
          return false;
      return true;
    }
  };

  class AabbTree
  {
  public:
    AabbTree() = default;
    explicit AabbTree(const std::vector<Box> &boxes);

    // New boxes (as many, in the same order) in the same hierarchy: each node's box is
    // made again from its children's, O(n). The splits stay those of the first boxes, so
    // queries slow down (never err) as the boxes move away from them.
    void
    refit(const std::vector<Box> &new_boxes);

    // Appends to `found` the index of every box that overlaps `query`.
    void
    find(const Box &query, std::vector<unsigned int> &found) const;

    // The smallest exact(k) over the stored boxes k, below `bound` (else `bound`):
    // branch and bound, a subtree skipped when lower(box) of its box is not below the
    // best found. lower(box) must bound exact(k) from below for every box k inside.
    template <typename Lower, typename Exact>
    double
    nearest(const Lower &lower, const Exact &exact, double bound) const
    {
      if (nodes.empty())
        return bound;
      std::vector<unsigned int> stack = {0};
      while (!stack.empty())
        {
          const Node &node = nodes[stack.back()];
          stack.pop_back();
          if (lower(node.box) >= bound)
            continue;
          if (node.count > 0)
            for (unsigned int k = node.first; k < node.first + node.count; ++k)
              bound = std::min(bound, exact(order[k]));
          else
            {
              stack.push_back(node.left);
              stack.push_back(node.right);
            }
        }
      return bound;
    }

    std::size_t
    size() const
    {
      return order.size();
    }

  private:
    struct Node
    {
      Box          box;
      unsigned int first, count; // a leaf's boxes: order[first, first + count)
      unsigned int left, right;  // children of an inner node (count == 0)
    };

    unsigned int
    build(const unsigned int first, const unsigned int count);

    std::vector<Box>          boxes;
    std::vector<Node>         nodes;
    std::vector<unsigned int> order;
  };
} // namespace clothsim::physics
