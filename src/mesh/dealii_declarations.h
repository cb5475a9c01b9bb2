#pragma once

// Declarations of deal.II's mesh and finite-element classes, for headers that only name
// them. Their own headers cost two to three seconds of compile time in every file that
// includes them; the files that use the classes include them (e.g.
// <deal.II/dofs/dof_handler.h>).

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
  template <int dim, int spacedim>
  class DoFHandler;
  template <int dim, int spacedim>
  class FESystem;
  template <int dim, int spacedim>
  class MappingFE;
  namespace parallel::fullydistributed
  {
    template <int dim, int spacedim>
    class Triangulation;
  }
} // namespace dealii
