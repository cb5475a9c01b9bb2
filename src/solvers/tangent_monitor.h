#pragma once

// Modified Newton's test of a worn-out tangent, as a NOX status test that never decides:
// after each iteration it asks for a new tangent if the last one reduced the residual by
// less than half or its step had to be cut.

#include "solvers/newton_solver.h"

#include <NOX_StatusTest_Generic.H>

namespace clothsim
{
  class TangentMonitor : public NOX::StatusTest::Generic
  {
  public:
    explicit TangentMonitor(NewtonSolver::TangentState &tangent)
      : tangent(tangent)
    {}

    NOX::StatusTest::StatusType
    checkStatus(const NOX::Solver::Generic &solver, NOX::StatusTest::CheckType) override;

    NOX::StatusTest::StatusType
    getStatus() const override
    {
      return NOX::StatusTest::Unconverged;
    }

    std::ostream &
    print(std::ostream &stream, int indent = 0) const override;

  private:
    NewtonSolver::TangentState &tangent;
  };
} // namespace clothsim
