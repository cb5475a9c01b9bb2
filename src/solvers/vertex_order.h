#pragma once

// A fill-reducing order from the mesh: METIS' nested dissection of the mesh's vertices
// instead of the unknowns, each unknown eliminated with its vertex or edge (Karypis &
// Kumar, SIAM J. Sci. Comput. 20, 1998, on the quotient graph; cf. Ashcraft, "Compressed
// graphs and the minimum degree algorithm", SIAM J. Sci. Comput. 16, 1995). The vertices'
// graph has a fraction of the unknowns' nodes, so it is ordered several times faster.

#include <deal.II/base/types.h>

#include "solvers/fill_reducing_order.h"
#include "solvers/supernodal_cholesky.h"

#include <Epetra_Map.h>

#include <array>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace clothsim
{
  // order[p] is the row eliminated p-th for a pattern whose rows belong to a mesh's
  // vertices: row i to the vertex vertices[i][0], or to the edge between it and
  // vertices[i][1] (vertices numbered 0 .. n_vertices - 1). METIS orders the vertices'
  // graph (two vertices adjacent where an entry couples their rows), and each row is
  // eliminated right after the first of its vertices in that order (a vertex's rows
  // before its edges'; after the later vertex instead: 7 times the operations). The
  // vertices' graph has a fraction of the rows' nodes, so METIS orders it 5 to 10 times
  // faster; on the swinging sheet with UFACTOR = 500 its orders cost 6 to 8 % fewer
  // operations than PORD's at N = 81 and 321 (PORD's are cheaper at N = 41 and 161),
  // and a fifth fewer than METIS on the rows for each rank's interior at N = 321
  // (README, "Several ranks: substructuring"). Nothing if METIS fails.
  std::optional<std::vector<int>>
  vertex_nested_dissection_order(int                                    n,
                                 const std::vector<int>                &rows,
                                 const std::vector<int>                &columns,
                                 const std::vector<std::array<int, 2>> &vertices,
                                 int                                    n_vertices,
                                 const NestedDissectionOptions         &options = {});

  // The vertices of the rows whose dofs are `row_dofs`, numbered 0, 1, ... in the
  // order of their names, and their number, from `mesh_dofs` (increasing) and each one's
  // vertex or edge's vertices `mesh_vertices` (vertices named by any distinct numbers).
  // Nothing unless every row is on the mesh.
  std::optional<std::pair<std::vector<std::array<int, 2>>, int>>
  rows_on_mesh(
    const std::vector<dealii::types::global_dof_index>                &row_dofs,
    const std::vector<dealii::types::global_dof_index>                &mesh_dofs,
    const std::vector<std::array<dealii::types::global_dof_index, 2>> &mesh_vertices);

  // Replaces `cholesky` (analysed, factors in single precision or not) by one analysed
  // in the vertices' order with UFACTOR = 500 if that costs fewer operations; whether
  // it did. n, rows, columns and value_index as given to SupernodalCholesky::analyse;
  // row i of the pattern is row matrix_rows[i] of `row_map` (local indices); the mesh
  // as for rows_on_mesh. Nothing changes if a row is not on the mesh or METIS fails.
  bool
  prefer_vertex_order(
    std::unique_ptr<SupernodalCholesky>                               &cholesky,
    bool                                                               single_precision,
    int                                                                n,
    const std::vector<int>                                            &rows,
    const std::vector<int>                                            &columns,
    const std::vector<int>                                            &value_index,
    const Epetra_Map                                                  &row_map,
    const std::vector<int>                                            &matrix_rows,
    const std::vector<dealii::types::global_dof_index>                &mesh_dofs,
    const std::vector<std::array<dealii::types::global_dof_index, 2>> &mesh_vertices);
} // namespace clothsim
