// clothsim: finite-element cloth and thin-shell simulator.
//
// Solves the motion of a thin sheet (membrane energy of the surface's Green strain,
// gravity, damping, pinned vertices) on a gmsh triangle mesh with implicit time stepping,
// Newton (NOX) and algebraic multigrid (ML), and writes VTK for ParaView. Sample command
// lines:
//   clothsim                                   # params/default.prm
//   clothsim params/hanging-sheet.prm --set "Time/End time=0.5" --output-dir /tmp/run
//   mpirun -np 2 clothsim params/hanging-sheet.prm
//   clothsim --print-parameters

#include <deal.II/base/mpi.h>

#include "app/application.h"

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  return clothsim::run_application(argc, argv);
}
