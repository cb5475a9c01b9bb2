#pragma once

// Summing a loop's contributions to a global vector by local index: each element or
// spring adds its local vector at the positions of its dofs in ghosted vectors (their
// local indices, mesh/ghosted_values.h), with no global-to-local lookup and no
// constraint check per entry; at the end one Epetra export adds the sums to the owned
// vector (the sums on ghost dofs to their owners). This replaces
// AffineConstraints::distribute_local_to_global into a Trilinos vector, which pays a
// lookup per entry (measured: a sixth of an explicit mass-spring run), and gives the
// same vector up to the order of summation: the entries of constrained dofs are dropped,
// as distribute_local_to_global drops them for the homogeneous constraints (lines
// without entries) that this program uses.

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <memory>
#include <vector>

class Epetra_BlockMap;
class Epetra_Export;

namespace clothsim::mesh
{
  using namespace dealii;

  class LocalSums
  {
  public:
    LocalSums();
    ~LocalSums();

    // Zeroes the sums for a loop over vectors with the layout of `ghosted` (every ghosted
    // vector of a model has the same).
    void
    start(const TrilinosWrappers::MPI::Vector &ghosted);

    // Adds `value` at the local index `local_dof` of ghosted vectors.
    void
    add(const int local_dof, const double value)
    {
      sums[local_dof] += value;
    }

    // Adds the sums to the owned vector `owned`, without the dofs that `constraints`
    // constrains. Like distribute_local_to_global, it leaves `owned` to be compressed
    // with VectorOperation::add.
    void
    add_to(TrilinosWrappers::MPI::Vector   &owned,
           const AffineConstraints<double> &constraints);

  private:
    std::vector<double> sums;
    // The constraints' lines at the last add_to() and their local indices (-1: absent).
    std::vector<types::global_dof_index> constrained;
    std::vector<int>                     constrained_local;
    std::unique_ptr<Epetra_BlockMap>     ghosted_map;
    std::unique_ptr<Epetra_Export>       exporter; // ghosted to owned layout, made once
  };
} // namespace clothsim::mesh
