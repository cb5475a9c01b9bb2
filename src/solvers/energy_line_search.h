#pragma once

// Backtracking line search on an objective whose gradient is the Newton residual F (an
// incremental potential), for NOX. Armijo condition Φ(x + α d) <= Φ(x) + c α F·d with c =
// 1e-4, step halving (Nocedal & Wright, "Numerical Optimization", alg. 3.1). Near the
// solution the decrease α F·d falls below the round-off of Φ itself (|Φ| ε); there the
// step is judged by the residual norm instead, so Newton's last iterations are not cut by
// noise. When no step of the 30 halvings decreases Φ, the search fails with step 0 and
// Newton with it (the time step is then cut); so does a stall, three searches in a row
// that kept less than 1/1024 of their longest step and left ‖F‖ within 1 %. The search
// starts from the problem's largest admissible step (contact: continuous collision
// detection), 1 without contact.

#include <NOX_LineSearch_Generic.H>
#include <NOX_LineSearch_UserDefinedFactory.H>

#include <functional>
#include <string>

namespace clothsim
{
  class EnergyLineSearch : public NOX::LineSearch::Generic
  {
  public:
    // objective(x): Φ at the group's solution vector x.
    using Objective = std::function<double(const NOX::Abstract::Vector &)>;
    // cap(x, d): the largest step along d from x that may be tried (<= 1).
    using StepCap =
      std::function<double(const NOX::Abstract::Vector &, const NOX::Abstract::Vector &)>;

    // adapt(x): at an accepted x, whether the problem changed itself there (then Φ and
    // F at x are taken again); may be empty.
    using Adapt = std::function<bool(const NOX::Abstract::Vector &)>;

    EnergyLineSearch(Objective          objective,
                     StepCap            cap,
                     Adapt              adapt,
                     const unsigned int max_halvings);

    bool
    compute(NOX::Abstract::Group        &group,
            double                      &step,
            const NOX::Abstract::Vector &direction,
            const NOX::Solver::Generic  &solver) override;

    // Why a solve failed at its cap of `iterations`: "no convergence in ...", and, if
    // the cap allowed less than 1 % of Newton's update in more than half of them, that
    // the step cap held the iterates back (collision detection or a tilt barrier: the
    // tangent's model then lets Newton push into a barrier; README, "Contact with
    // obstacles").
    std::string
    iteration_cap_message(const unsigned int iterations) const;

    // Why the last search failed: no decrease at any step, or a stall (the last
    // stall_count searches each kept less than stall_fraction of their longest step and
    // left ‖F‖ above stall_residual of what it was).
    std::string
    failure_message() const;

    static constexpr double       stall_fraction = 1. / 1024.;
    static constexpr double       stall_residual = 0.99;
    static constexpr unsigned int stall_count    = 3;

  private:
    unsigned int       n_held_back = 0;
    Objective          objective;
    StepCap            cap;
    Adapt              adapt;
    const unsigned int max_halvings;
    // Φ at the step accepted last: the next search starts from there (one evaluation
    // saved).
    bool   have_accepted_value = false;
    double accepted_value      = 0.;
    // Searches in a row that kept less than stall_fraction of their longest step, and
    // whether the last one failed for that.
    unsigned int n_stalled = 0;
    bool         stalled   = false;
  };

  // NOX builds line searches through a factory ("User Defined Line Search Factory").
  class EnergyLineSearchFactory : public NOX::LineSearch::UserDefinedFactory
  {
  public:
    explicit EnergyLineSearchFactory(Teuchos::RCP<EnergyLineSearch> line_search)
      : line_search(line_search)
    {}

    Teuchos::RCP<NOX::LineSearch::Generic>
    buildLineSearch(const Teuchos::RCP<NOX::GlobalData> &,
                    Teuchos::ParameterList &) const override
    {
      return line_search;
    }

  private:
    Teuchos::RCP<EnergyLineSearch> line_search;
  };
} // namespace clothsim
