#pragma once

// A bounding-volume hierarchy of axis-aligned boxes (the broad phase of contact): built
// once by median splits along the longest axis of the boxes' centres, queried with a
// box for every stored box that overlaps it. Build O(n log n); a query visits
// O(log n + k) nodes for k overlaps of small boxes.

#include <deal.II/base/point.h>

#include <algorithm>
#include <cmath>
#include <utility>
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

    // The sum of the box's extents along the axes.
    double
    size() const
    {
      return (upper[0] - lower[0]) + (upper[1] - lower[1]) + (upper[2] - lower[2]);
    }

    // Whether this box grown by `margin` overlaps `other`.
    bool
    within(const Box &other, const double margin) const
    {
      for (unsigned int d = 0; d < 3; ++d)
        if (lower[d] - margin > other.upper[d] || other.lower[d] - margin > upper[d])
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

    // Calls visit(i, j) for every stored box i and every box j of `other` within
    // `margin` of each other (Box::within), descending both hierarchies at once: a pair
    // of nodes apart is never opened, so each box is not looked up from the root. The
    // order is fixed by the two hierarchies. `margin` is read at every test.
    template <typename Visit>
    void
    for_each_overlap(const AabbTree &other,
                     const double   &margin,
                     const Visit    &visit) const
    {
      descend(other, false, margin, visit);
    }

    // The same within this hierarchy: every pair i < j of its boxes within `margin`.
    template <typename Visit>
    void
    for_each_overlap(const double &margin, const Visit &visit) const
    {
      descend(*this, true, margin, visit);
    }

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

    // The i-th stored box (as given, or at the last refit).
    const Box &
    box(const unsigned int i) const
    {
      return boxes[i];
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

    template <typename Visit>
    void
    descend(const AabbTree &other,
            const bool      self,
            const double   &margin,
            const Visit    &visit) const
    {
      if (nodes.empty() || other.nodes.empty())
        return;
      std::vector<std::pair<unsigned int, unsigned int>> stack = {{0u, 0u}};
      while (!stack.empty())
        {
          const auto [a, b] = stack.back();
          stack.pop_back();
          const Node &A = nodes[a], &B = other.nodes[b];
          if (self && a == b)
            {
              if (A.count > 0)
                {
                  for (unsigned int i = A.first; i < A.first + A.count; ++i)
                    for (unsigned int j = i + 1; j < A.first + A.count; ++j)
                      if (boxes[order[i]].within(boxes[order[j]], margin))
                        visit(std::min(order[i], order[j]), std::max(order[i], order[j]));
                }
              else
                {
                  stack.emplace_back(A.right, A.right);
                  stack.emplace_back(A.left, A.right);
                  stack.emplace_back(A.left, A.left);
                }
              continue;
            }
          if (!A.box.within(B.box, margin))
            continue;
          if (A.count > 0 && B.count > 0)
            {
              for (unsigned int i = A.first; i < A.first + A.count; ++i)
                for (unsigned int j = B.first; j < B.first + B.count; ++j)
                  if (boxes[order[i]].within(other.boxes[other.order[j]], margin))
                    {
                      if (self)
                        visit(std::min(order[i], other.order[j]),
                              std::max(order[i], other.order[j]));
                      else
                        visit(order[i], other.order[j]);
                    }
            }
          else if (B.count > 0 || (A.count == 0 && A.box.size() >= B.box.size()))
            {
              // Open this hierarchy's node: the other's is a leaf, or both are inner
              // nodes and this one's box is the larger (this one on a tie).
              stack.emplace_back(A.right, b);
              stack.emplace_back(A.left, b);
            }
          else
            {
              stack.emplace_back(a, B.right);
              stack.emplace_back(a, B.left);
            }
        }
    }

    std::vector<Box>          boxes;
    std::vector<Node>         nodes;
    std::vector<unsigned int> order;
  };
} // namespace clothsim::physics
