#pragma once

// Reading a ghosted Trilinos vector inside element and spring loops by local index: the
// position of a dof in the vector's Epetra map (its LID), computed once at set-up, so
// that a loop does not pay a global-to-local lookup per entry (measured: a third of an
// explicit mass-spring step). Every ghosted vector of a model is made by the same
// initialize_ghosted() and shares one map, so one set of local indices serves them all.

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_MultiVector.h>

namespace clothsim
{
  using namespace dealii;

  // The local index of `dof` in `ghosted_prototype`'s map (-1 if absent).
  inline int
  local_index(const TrilinosWrappers::MPI::Vector &ghosted_prototype,
              const types::global_dof_index        dof)
  {
    return ghosted_prototype.trilinos_partitioner().LID(
      static_cast<TrilinosWrappers::types::int_type>(dof));
  }

  // The locally stored values of a ghosted vector, indexed by local_index().
  // `expected_size`: the number of locally relevant dofs (checked in debug builds).
  inline const double *
  ghosted_values(const TrilinosWrappers::MPI::Vector &ghosted,
                 const unsigned int                   expected_size)
  {
    AssertDimension(static_cast<unsigned int>(ghosted.trilinos_vector().MyLength()),
                    expected_size);
    (void)expected_size;
    return ghosted.trilinos_vector()[0];
  }
} // namespace clothsim
