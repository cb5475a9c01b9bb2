#include "solvers/energy_line_search.h"

#include <NOX_Abstract_Group.H>
#include <NOX_Abstract_Vector.H>
#include <NOX_Solver_Generic.H>

#include <cmath>
#include <limits>

namespace clothsim
{
  EnergyLineSearch::EnergyLineSearch(Objective          objective,
                                     StepCap            cap,
                                     Adapt              adapt,
                                     const unsigned int max_halvings)
    : objective(std::move(objective))
    , cap(std::move(cap))
    , adapt(std::move(adapt))
    , max_halvings(max_halvings)
  {}


  bool
  EnergyLineSearch::compute(NOX::Abstract::Group        &group,
                            double                      &step,
                            const NOX::Abstract::Vector &direction,
                            const NOX::Solver::Generic  &solver)
  {
    constexpr double            sufficient_decrease = 1e-4;
    const NOX::Abstract::Group &old_group           = solver.getPreviousSolutionGroup();
    const double                old_value =
      have_accepted_value ? accepted_value : objective(old_group.getX());
    const double old_norm = old_group.getNormF();
    const double slope    = old_group.getF().innerProduct(direction);
    // The objective's own resolution: changes below this are round-off.
    const double noise =
      100. * std::numeric_limits<double>::epsilon() * std::abs(old_value);

    // A cap of zero (an iterate on a barrier's limit) leaves no step: the search fails
    // at once (accepting a zero step would change nothing until the iteration cap).
    step = std::min(1., cap(old_group.getX(), direction));
    if (step < 1e-2)
      ++n_held_back;
    const double longest = step;
    // No decrease at any step: fail the solve at once (NOX fails on a zero step), back at
    // the old iterate. Continuing from a tiny step would only repeat the same direction
    // until the iteration cap (measured: 175 wasted iterations on a folding step).
    const auto fail = [&]() {
      step = 0.;
      group.computeX(old_group, direction, step);
      group.computeF();
      return false;
    };
    // A step kept far below the longest one tried that left the residual as it was,
    // stall_count times in a row, is a stall: the same direction crawled along
    // (measured: 19 Newton iterations in a row on steps of 2⁻⁷ to 2⁻³⁰ while ‖F‖ went
    // from 0.840 to 0.835 N, the sheet on a sphere at N = 81), and the solve fails too.
    const auto accept = [&](double value) {
      // The problem may change at the accepted iterate (contact's adaptive barrier
      // stiffness): then Φ and F are taken there again.
      if (adapt && adapt(group.getX()))
        {
          value = objective(group.getX());
          group.computeX(old_group, direction, step);
          group.computeF();
        }
      have_accepted_value = true;
      accepted_value      = value;
      const bool crawl =
        step < stall_fraction * longest && group.getNormF() > stall_residual * old_norm;
      n_stalled = crawl ? n_stalled + 1 : 0;
      if (n_stalled < stall_count)
        return true;
      stalled = true;
      return fail();
    };
    for (unsigned int cut = 0; cut <= max_halvings && step > 0.; ++cut, step *= 0.5)
      {
        group.computeX(old_group, direction, step);
        const double value = objective(group.getX());
        if (!std::isfinite(value))
          continue;
        if (value <= old_value + sufficient_decrease * step * slope)
          {
            group.computeF();
            return accept(value);
          }
        // Below the objective's resolution: accept if the residual decreases.
        if (std::abs(step * slope) < noise)
          {
            group.computeF();
            if (group.getNormF() < old_norm)
              return accept(value);
          }
      }
    return fail();
  }


  std::string
  EnergyLineSearch::failure_message() const
  {
    if (stalled)
      return "the line search stalled: " + std::to_string(stall_count) +
             " Newton updates in a row kept less than 1/" +
             std::to_string(static_cast<int>(1. / stall_fraction)) +
             " of their length and left the residual within 1 % (Φ decreases only so "
             "close to the iterate)";
    return "line search found no decrease (within its step cap)";
  }


  std::string
  EnergyLineSearch::iteration_cap_message(const unsigned int iterations) const
  {
    std::string message =
      "no convergence in " + std::to_string(iterations) + " iterations";
    if (2 * n_held_back > iterations)
      message += "; the line search's step cap (collision detection or a tilt barrier) "
                 "held " +
                 std::to_string(n_held_back) + " of them below 1 % of Newton's update";
    return message;
  }
} // namespace clothsim
