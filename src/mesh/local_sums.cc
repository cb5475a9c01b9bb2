#include "mesh/local_sums.h"

#include <deal.II/lac/exceptions.h>

#include <Epetra_BlockMap.h>
#include <Epetra_Export.h>
#include <Epetra_Vector.h>

namespace clothsim::mesh
{
  LocalSums::LocalSums() = default;

  LocalSums::~LocalSums() = default;


  void
  LocalSums::start(const TrilinosWrappers::MPI::Vector &ghosted)
  {
    if (ghosted_map == nullptr)
      ghosted_map = std::make_unique<Epetra_BlockMap>(ghosted.trilinos_partitioner());
    AssertDimension(ghosted_map->NumMyElements(),
                    ghosted.trilinos_partitioner().NumMyElements());
    sums.assign(ghosted_map->NumMyElements(), 0.);
  }


  void
  LocalSums::add_to(TrilinosWrappers::MPI::Vector   &owned,
                    const AffineConstraints<double> &constraints)
  {
    Assert(ghosted_map != nullptr, ExcMessage("start() first"));
    for (const auto &line : constraints.get_lines())
      {
        AssertThrow(line.entries.empty() && line.inhomogeneity == 0.,
                    ExcMessage("only homogeneous constraints without entries"));
        const int local =
          ghosted_map->LID(static_cast<TrilinosWrappers::types::int_type>(line.index));
        if (local >= 0)
          sums[local] = 0.;
      }
    if (exporter == nullptr)
      exporter =
        std::make_unique<Epetra_Export>(*ghosted_map, owned.trilinos_partitioner());
    const Epetra_Vector source(View, *ghosted_map, sums.data());
    // AddLocalAlso: the sums on owned dofs are added too (Add would overwrite them).
    const int error =
      owned.trilinos_vector().Export(source, *exporter, Epetra_AddLocalAlso);
    AssertThrow(error == 0, LACExceptions::ExcTrilinosError(error));
  }
} // namespace clothsim::mesh
