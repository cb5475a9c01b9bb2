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
    // The constrained dofs' local indices, looked up again only when the constraints'
    // lines differ from the last call's (a hash lookup each on a rank whose indices are
    // not contiguous; the director angles' unused dofs make one line per vertex).
    const auto &lines = constraints.get_lines();
    bool        same  = lines.size() == constrained.size();
    std::size_t k     = 0;
    for (auto line = lines.begin(); same && line != lines.end(); ++line, ++k)
      same = line->index == constrained[k] && line->entries.empty() &&
             line->inhomogeneity == 0.;
    if (!same)
      {
        constrained.clear();
        constrained_local.clear();
        for (const auto &line : lines)
          {
            AssertThrow(line.entries.empty() && line.inhomogeneity == 0.,
                        ExcMessage("only homogeneous constraints without entries"));
            constrained.push_back(line.index);
            constrained_local.push_back(ghosted_map->LID(
              static_cast<TrilinosWrappers::types::int_type>(line.index)));
          }
      }
    for (const int local : constrained_local)
      if (local >= 0)
        sums[local] = 0.;
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
