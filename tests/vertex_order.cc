// The fill-reducing order from the mesh's vertices (solvers/vertex_order.h) on the
// swinging sheet's pattern (tests/sheet_pattern.h, N = 41).
// - The order is a permutation; each vertex's rows come together, and each edge's row
//   after the rows of the first of its two vertices in the order (and before the next
//   vertex's).
// - Its cost against METIS on the unknowns' graph (the order the substructured solver
//   used for it without the mesh): N = 41, UFACTOR = 500, measured 3.7e7 against 4.3e7
//   operations (bound: not above it); and against the natural (row by row) order,
//   thousands of times fewer (bound: a hundredth).
// - The factorisation in that order solves b = A x* to single precision's accuracy.
// - rows_on_mesh numbers the N² vertices 0 .. N² - 1 and refuses a row that is not on the
//   mesh; prefer_vertex_order replaces an analysis in the natural order (and says so),
//   and keeps one in its own order (not cheaper than itself).

#include "solvers/vertex_order.h"

#include "solvers/fill_reducing_order.h"
#include "solvers/supernodal_cholesky.h"

#include "sheet_pattern.h"
#include "test_checks.h"

#include <Epetra_MpiComm.h>

#include <random>

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  double
  operations(const SheetPattern &sheet, const std::vector<int> &order)
  {
    SupernodalCholesky cholesky;
    cholesky.analyse(sheet.n, sheet.rows, sheet.columns, order);
    return cholesky.operations();
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment         environment(argc, argv);
  ConditionalOStream &out   = environment.pcout;
  const int           N     = 41;
  const SheetPattern  sheet = sheet_pattern(N, 20261130);

  const auto by_vertices = vertex_nested_dissection_order(
    sheet.n, sheet.rows, sheet.columns, sheet.vertices, sheet.n_vertices, {500, -1});
  check(out, by_vertices.has_value(), "METIS orders the vertices");
  const std::vector<int> &order = *by_vertices;
  std::vector<int>        position(sheet.n, -1);
  bool                    permutation = static_cast<int>(order.size()) == sheet.n;
  for (int p = 0; permutation && p < sheet.n; ++p)
    {
      permutation = order[p] >= 0 && order[p] < sheet.n && position[order[p]] < 0;
      if (permutation)
        position[order[p]] = p;
    }
  check(out, permutation, "the order is a permutation of the 9,923 rows");

  // Walking the order: a vertex's three rows, then the rows of the edges whose first
  // vertex it is, then the next vertex.
  std::vector<int> vertex_position(sheet.n_vertices, -1);
  int              n_vertices_seen = 0;
  bool             grouped         = permutation;
  for (int p = 0; grouped && p < sheet.n; ++p)
    {
      const auto [a, b] = sheet.vertices[order[p]];
      if (a == b && vertex_position[a] < 0)
        {
          vertex_position[a] = n_vertices_seen++;
          grouped            = p + 2 < sheet.n && sheet.vertices[order[p + 1]][0] == a &&
                    sheet.vertices[order[p + 2]][0] == a;
          p += 2;
        }
      else
        // An edge: its first vertex is the last vertex met, its other one comes later.
        grouped =
          a != b &&
          std::max(vertex_position[a], vertex_position[b]) == n_vertices_seen - 1 &&
          std::min(vertex_position[a], vertex_position[b]) < 0;
    }
  check(out,
        grouped && n_vertices_seen == sheet.n_vertices,
        "each vertex's rows together, each edge's row after its first vertex's");

  const auto unknowns_graph = nested_dissection_order(sheet.n, sheet.rows, sheet.columns);
  std::vector<int> natural(sheet.n);
  for (int i = 0; i < sheet.n; ++i)
    natural[i] = i;
  const double vertex_operations = operations(sheet, order);
  check_at_most(out,
                "operations, the vertices' order (UFACTOR 500) over METIS' on the "
                "unknowns' graph",
                vertex_operations / operations(sheet, *unknowns_graph),
                1.);
  check_below(out,
              "operations, the vertices' order over the natural order's",
              vertex_operations / operations(sheet, natural),
              0.01);

  {
    SupernodalCholesky cholesky;
    cholesky.analyse(sheet.n, sheet.rows, sheet.columns, order);
    check(out, cholesky.factorize(sheet.values.data()), "it factorises in that order");
    std::mt19937                           random(7);
    std::uniform_real_distribution<double> entry(-1., 1.);
    std::vector<double>                    exact(sheet.n), x(sheet.n, 0.);
    for (double &value : exact)
      value = entry(random);
    for (std::size_t k = 0; k < sheet.rows.size(); ++k)
      {
        x[sheet.rows[k]] += sheet.values[k] * exact[sheet.columns[k]];
        if (sheet.rows[k] != sheet.columns[k])
          x[sheet.columns[k]] += sheet.values[k] * exact[sheet.rows[k]];
      }
    cholesky.solve(x.data());
    double error = 0., size = 0.;
    for (int i = 0; i < sheet.n; ++i)
      {
        error = std::max(error, std::abs(x[i] - exact[i]));
        size  = std::max(size, std::abs(exact[i]));
      }
    check_below(out, "its solve, largest error over largest entry", error / size, 1e-3);
  }

  // The mesh as a model gives it: each row's dof (here its index) and its vertices named
  // by their first displacement dof.
  std::vector<dealii::types::global_dof_index>                mesh_dofs(sheet.n);
  std::vector<std::array<dealii::types::global_dof_index, 2>> mesh_vertices(sheet.n);
  for (int i = 0; i < sheet.n; ++i)
    {
      mesh_dofs[i]     = i;
      mesh_vertices[i] = {{3u * sheet.vertices[i][0], 3u * sheet.vertices[i][1]}};
    }
  const auto numbered = rows_on_mesh(mesh_dofs, mesh_dofs, mesh_vertices);
  check(out,
        numbered && numbered->second == sheet.n_vertices &&
          numbered->first == sheet.vertices,
        "rows_on_mesh numbers the 1,681 vertices by their names");
  std::vector<dealii::types::global_dof_index> off_mesh = mesh_dofs;
  off_mesh.push_back(sheet.n);
  check(out,
        !rows_on_mesh(off_mesh, mesh_dofs, mesh_vertices),
        "rows_on_mesh refuses a row that is not on the mesh");

  const Epetra_MpiComm comm(MPI_COMM_SELF);
  const Epetra_Map     row_map(sheet.n, 0, comm);
  auto                 cholesky = std::make_unique<SupernodalCholesky>();
  cholesky->analyse(sheet.n, sheet.rows, sheet.columns, natural);
  const double natural_operations = cholesky->operations();
  const auto   prefer             = [&]() {
    return prefer_vertex_order(cholesky,
                               true,
                               sheet.n,
                               sheet.rows,
                               sheet.columns,
                               {},
                               row_map,
                               natural,
                               mesh_dofs,
                               mesh_vertices);
  };
  const bool replaced = prefer();
  check(out,
        replaced && cholesky->operations() == vertex_operations &&
          cholesky->operations() < natural_operations,
        "prefer_vertex_order replaces the natural order's analysis by the vertices'");
  check(out, !prefer(), "and keeps that one (the same cost is not cheaper)");
  return finish_tally(out);
}
