#pragma once

// The pattern of the swinging sheet's tangent with SPD values, for the factorisation's
// tests and benchmark: an N x N-vertex square with alternating diagonals (as
// meshes/swing-N.geo), three displacement rows per vertex (3v + c), then one angle row
// per edge (numbered as met), each triangle coupling its vertices' and edges' rows (a 12
// x 12 element block). Off-diagonal entries are drawn in [-1, 0), each diagonal entry is
// 1 + 1e-4 times the absolute sum of its row (diagonally dominant, so SPD). The excess is
// about the swinging sheet's mass term against its stiffness: with more (1 + the sum,
// say), the factor's entries decay with the distance in the mesh to below single
// precision's normal range at N = 321 (unflushed, those denormals made a factorisation 14
// times slower; solvers/flush_denormals.h now flushes them).

#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace clothsim::test
{
  struct SheetPattern
  {
    int                 n = 0, n_vertices = 0;
    std::vector<int>    rows, columns; // the upper triangle, each entry once, 0-based
    std::vector<double> values;
    // Each row's vertex {v, v}, or its edge's two vertices.
    std::vector<std::array<int, 2>> vertices;
  };

  inline SheetPattern
  sheet_pattern(const int N, const unsigned int seed)
  {
    SheetPattern sheet;
    sheet.n_vertices  = N * N;
    const auto vertex = [N](const int i, const int j) { return i + N * j; };
    for (int v = 0; v < N * N; ++v)
      for (int c = 0; c < 3; ++c)
        sheet.vertices.push_back({{v, v}});
    std::map<std::pair<int, int>, int> edges;
    const auto                         edge = [&](const int a, const int b) {
      const auto [it, added] =
        edges.emplace(std::minmax(a, b), static_cast<int>(sheet.vertices.size()));
      if (added)
        sheet.vertices.push_back({{a, b}});
      return it->second;
    };
    std::map<std::pair<int, int>, double>  upper;
    std::mt19937                           random(seed);
    std::uniform_real_distribution<double> entry(-1., 0.);
    for (int j = 0; j + 1 < N; ++j)
      for (int i = 0; i + 1 < N; ++i)
        {
          const int v00 = vertex(i, j), v10 = vertex(i + 1, j), v01 = vertex(i, j + 1),
                    v11                   = vertex(i + 1, j + 1);
          const bool               up     = (i + j) % 2 == 0;
          const std::array<int, 3> first  = {{v00, v10, up ? v11 : v01}},
                                   second = {{up ? v00 : v10, v11, v01}};
          for (const auto &t : {first, second})
            {
              std::array<int, 12> rows;
              for (int a = 0; a < 3; ++a)
                for (int c = 0; c < 3; ++c)
                  rows[3 * a + c] = 3 * t[a] + c;
              for (int a = 0; a < 3; ++a)
                rows[9 + a] = edge(t[(a + 1) % 3], t[(a + 2) % 3]);
              for (int a = 0; a < 12; ++a)
                for (int b = a + 1; b < 12; ++b)
                  upper[std::minmax(rows[a], rows[b])] += entry(random);
            }
        }
    sheet.n = static_cast<int>(sheet.vertices.size());
    std::vector<double> diagonal(sheet.n, 0.);
    for (const auto &[key, value] : upper)
      {
        diagonal[key.first] -= value;
        diagonal[key.second] -= value;
      }
    for (int i = 0; i < sheet.n; ++i)
      upper[{i, i}] = (1. + 1e-4) * diagonal[i];
    for (const auto &[key, value] : upper)
      {
        sheet.rows.push_back(key.first);
        sheet.columns.push_back(key.second);
        sheet.values.push_back(value);
      }
    return sheet;
  }
} // namespace clothsim::test
