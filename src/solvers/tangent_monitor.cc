#include "solvers/tangent_monitor.h"

#include <NOX_Abstract_Group.H>
#include <NOX_Solver_LineSearchBased.H>

#include <string>

namespace clothsim
{
  NOX::StatusTest::StatusType
  TangentMonitor::checkStatus(const NOX::Solver::Generic &solver,
                              NOX::StatusTest::CheckType)
  {
    if (solver.getNumIterations() > 0)
      {
        const auto *line_search =
          dynamic_cast<const NOX::Solver::LineSearchBased *>(&solver);
        const bool cut = line_search != nullptr && line_search->getStepSize() != 1.;
        if (cut || solver.getSolutionGroup().getNormF() >
                     0.5 * solver.getPreviousSolutionGroup().getNormF())
          tangent.refresh = true;
      }
    return NOX::StatusTest::Unconverged;
  }


  std::ostream &
  TangentMonitor::print(std::ostream &stream, int indent) const
  {
    return stream << std::string(indent, ' ') << "tangent reuse monitor\n";
  }
} // namespace clothsim
