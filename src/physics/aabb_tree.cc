#include "physics/aabb_tree.h"

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <array>
#include <numeric>

namespace clothsim::physics
{
  AabbTree::AabbTree(const std::vector<Box> &boxes)
    : boxes(boxes)
    , order(boxes.size())
  {
    std::iota(order.begin(), order.end(), 0u);
    if (!boxes.empty())
      build(0, boxes.size());
  }


  unsigned int
  AabbTree::build(const unsigned int first, const unsigned int count)
  {
    const unsigned int index = nodes.size();
    nodes.push_back(Node{boxes[order[first]], first, count, 0, 0});
    Box centres{Point<3>(), Point<3>()};
    for (unsigned int k = first; k < first + count; ++k)
      {
        const Box     &box = boxes[order[k]];
        const Point<3> centre((box.lower + box.upper) / 2.);
        for (unsigned int d = 0; d < 3; ++d)
          {
            nodes[index].box.lower[d] = std::min(nodes[index].box.lower[d], box.lower[d]);
            nodes[index].box.upper[d] = std::max(nodes[index].box.upper[d], box.upper[d]);
            centres.lower[d] =
              k == first ? centre[d] : std::min(centres.lower[d], centre[d]);
            centres.upper[d] =
              k == first ? centre[d] : std::max(centres.upper[d], centre[d]);
          }
      }
    if (count <= 4)
      return index;

    // Split at the median centre along the longest axis of the centres' box.
    const Tensor<1, 3> extent = centres.upper - centres.lower;
    const unsigned int axis   = extent[0] >= extent[1] && extent[0] >= extent[2] ? 0
                                : extent[1] >= extent[2]                         ? 1
                                                                                 : 2;
    const unsigned int half   = count / 2;
    std::nth_element(order.begin() + first,
                     order.begin() + first + half,
                     order.begin() + first + count,
                     [&](const unsigned int a, const unsigned int b) {
                       return boxes[a].lower[axis] + boxes[a].upper[axis] <
                              boxes[b].lower[axis] + boxes[b].upper[axis];
                     });
    const unsigned int left  = build(first, half);
    const unsigned int right = build(first + half, count - half);
    nodes[index].count       = 0;
    nodes[index].left        = left;
    nodes[index].right       = right;
    return index;
  }


  void
  AabbTree::refit(const std::vector<Box> &new_boxes)
  {
    AssertDimension(new_boxes.size(), boxes.size());
    boxes = new_boxes;
    // Children come after their parent in `nodes` (built depth-first).
    for (unsigned int n = nodes.size(); n-- > 0;)
      {
        Node &node = nodes[n];
        if (node.count > 0)
          {
            node.box = boxes[order[node.first]];
            for (unsigned int k = node.first + 1; k < node.first + node.count; ++k)
              node.box = node.box.merged(boxes[order[k]]);
          }
        else
          node.box = nodes[node.left].box.merged(nodes[node.right].box);
      }
  }


  void
  AabbTree::find(const Box &query, std::vector<unsigned int> &found) const
  {
    if (nodes.empty())
      return;
    // Depth-first; the stack holds at most one node per level plus one (median splits
    // keep the depth at log2 of the size), so no allocation per query.
    std::array<unsigned int, 128> stack;
    unsigned int                  size = 0;
    stack[size++]                      = 0;
    while (size > 0)
      {
        const Node &node = nodes[stack[--size]];
        if (!node.box.overlaps(query))
          continue;
        if (node.count > 0)
          {
            for (unsigned int k = node.first; k < node.first + node.count; ++k)
              if (boxes[order[k]].overlaps(query))
                found.push_back(order[k]);
          }
        else
          {
            Assert(size + 2 <= stack.size(), ExcInternalError());
            stack[size++] = node.left;
            stack[size++] = node.right;
          }
      }
  }
} // namespace clothsim::physics
