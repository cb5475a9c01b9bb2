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

#include "app/application.h"
#include "app/mpi_session.h"

int
main(int argc, char **argv)
{
  clothsim::MpiSession mpi(argc, argv);
  return clothsim::run_application(argc, argv);
}
