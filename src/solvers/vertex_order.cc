#include "solvers/vertex_order.h"

#include <algorithm>
#include <cstdint>

namespace clothsim
{
  std::optional<std::vector<int>>
  vertex_nested_dissection_order(const int                              n,
                                 const std::vector<int>                &rows,
                                 const std::vector<int>                &columns,
                                 const std::vector<std::array<int, 2>> &vertices,
                                 const int                              n_vertices,
                                 const NestedDissectionOptions         &options)
  {
    // Each row's neighbours, both ways (the pattern holds one triangle), and each
    // vertex's rows: compressed lists.
    const auto compress = [](const int                               size,
                             const std::vector<std::pair<int, int>> &items,
                             std::vector<int>                       &start,
                             std::vector<int>                       &list) {
      start.assign(size + 1, 0);
      for (const auto &[owner, item] : items)
        ++start[owner + 1];
      for (int i = 0; i < size; ++i)
        start[i + 1] += start[i];
      list.resize(items.size());
      std::vector<int> next(start.begin(), start.end() - 1);
      for (const auto &[owner, item] : items)
        list[next[owner]++] = item;
    };
    std::vector<std::pair<int, int>> items;
    // Reserved: at N = 321, growing it took a third of this function's time.
    items.reserve(2 * rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k)
      if (rows[k] != columns[k])
        {
          items.emplace_back(rows[k], columns[k]);
          items.emplace_back(columns[k], rows[k]);
        }
    std::vector<int> neighbour_start, neighbours, row_start, rows_of_vertex;
    compress(n, items, neighbour_start, neighbours);
    items.clear();
    for (int i = 0; i < n; ++i)
      {
        items.emplace_back(vertices[i][0], i);
        if (vertices[i][1] != vertices[i][0])
          items.emplace_back(vertices[i][1], i);
      }
    compress(n_vertices, items, row_start, rows_of_vertex);
    // The vertices' graph, each pair once as (a, b), a < b, in increasing order: b is a
    // vertex of a row of a, or of a row coupled to one (marked once per a).
    std::vector<int> vertex_rows, vertex_columns, mark(n_vertices, -1), found;
    for (int a = 0; a < n_vertices; ++a)
      {
        found.clear();
        const auto meet = [&](const int row) {
          for (const int b : vertices[row])
            if (b > a && mark[b] != a)
              {
                mark[b] = a;
                found.push_back(b);
              }
        };
        for (int r = row_start[a]; r < row_start[a + 1]; ++r)
          {
            const int row = rows_of_vertex[r];
            meet(row);
            for (int k = neighbour_start[row]; k < neighbour_start[row + 1]; ++k)
              meet(neighbours[k]);
          }
        std::sort(found.begin(), found.end());
        for (const int b : found)
          {
            vertex_rows.push_back(a);
            vertex_columns.push_back(b);
          }
      }
    const auto vertex_order =
      nested_dissection_order(n_vertices, vertex_rows, vertex_columns, options);
    if (!vertex_order)
      return std::nullopt;
    std::vector<int> position(n_vertices);
    for (int p = 0; p < n_vertices; ++p)
      position[(*vertex_order)[p]] = p;
    // Rows by the first of their vertices' positions, edge rows after vertex rows.
    std::vector<std::pair<std::int64_t, int>> keys(n);
    for (int i = 0; i < n; ++i)
      {
        const auto [a, b] = vertices[i];
        keys[i] = {2 * std::int64_t(std::min(position[a], position[b])) + (a != b), i};
      }
    std::sort(keys.begin(), keys.end());
    std::vector<int> order(n);
    for (int p = 0; p < n; ++p)
      order[p] = keys[p].second;
    return order;
  }


  std::optional<std::pair<std::vector<std::array<int, 2>>, int>>
  rows_on_mesh(
    const std::vector<dealii::types::global_dof_index>                &row_dofs,
    const std::vector<dealii::types::global_dof_index>                &mesh_dofs,
    const std::vector<std::array<dealii::types::global_dof_index, 2>> &mesh_vertices)
  {
    std::vector<dealii::types::global_dof_index> names;
    names.reserve(2 * mesh_vertices.size());
    for (const auto &pair : mesh_vertices)
      names.insert(names.end(), pair.begin(), pair.end());
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    const auto number = [&names](const dealii::types::global_dof_index name) {
      return static_cast<int>(std::lower_bound(names.begin(), names.end(), name) -
                              names.begin());
    };
    std::vector<std::array<int, 2>> vertices(row_dofs.size());
    for (std::size_t i = 0; i < row_dofs.size(); ++i)
      {
        const auto found =
          std::lower_bound(mesh_dofs.begin(), mesh_dofs.end(), row_dofs[i]);
        if (found == mesh_dofs.end() || *found != row_dofs[i])
          return std::nullopt;
        const auto &pair = mesh_vertices[found - mesh_dofs.begin()];
        vertices[i]      = {{number(pair[0]), number(pair[1])}};
      }
    return std::make_pair(std::move(vertices), static_cast<int>(names.size()));
  }


  bool
  prefer_vertex_order(
    std::unique_ptr<SupernodalCholesky>                               &cholesky,
    const bool                                                         single_precision,
    const int                                                          n,
    const std::vector<int>                                            &rows,
    const std::vector<int>                                            &columns,
    const std::vector<int>                                            &value_index,
    const Epetra_Map                                                  &row_map,
    const std::vector<int>                                            &matrix_rows,
    const std::vector<dealii::types::global_dof_index>                &mesh_dofs,
    const std::vector<std::array<dealii::types::global_dof_index, 2>> &mesh_vertices)
  {
    std::vector<dealii::types::global_dof_index> row_dofs(matrix_rows.size());
    for (std::size_t i = 0; i < matrix_rows.size(); ++i)
      row_dofs[i] = row_map.GID64(matrix_rows[i]);
    const auto vertices = rows_on_mesh(row_dofs, mesh_dofs, mesh_vertices);
    if (!vertices)
      return false;
    const auto order = vertex_nested_dissection_order(
      n, rows, columns, vertices->first, vertices->second, {500, -1});
    if (!order)
      return false;
    auto candidate = std::make_unique<SupernodalCholesky>(single_precision);
    candidate->analyse(n, rows, columns, *order, value_index);
    if (candidate->operations() >= cholesky->operations())
      return false;
    cholesky = std::move(candidate);
    return true;
  }
} // namespace clothsim
