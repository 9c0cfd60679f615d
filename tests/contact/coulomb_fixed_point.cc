// contact::CoulombFixedPoint, the tests every Coulomb loop shares (dual
// ContactSolver, primal UzawaCGC): for given sequences of relative changes
// of psi, the state after each update and the message, against the rules of
// coulomb_fixed_point.h: non-finite first, then the tolerance, then
// `Divergence window' consecutive growths, then the iteration limit; the
// relative change divides by ||psi|| unless psi is zero.
#include <contact/coulomb_fixed_point.h>

#include <cmath>
#include <limits>
#include <vector>

#include "test_tools.h"

using dualcontact::contact::CoulombFixedPoint;
using dualcontact::contact::CoulombParameters;
using State = CoulombFixedPoint::State;

namespace
{
  /** The states after feeding @p changes until the loop stops. */
  std::vector<State>
  run(CoulombFixedPoint &fixed_point, const std::vector<double> &changes)
  {
    std::vector<State> states;
    for (const double change : changes)
    {
      states.push_back(fixed_point.record_change(change));
      if (states.back() != State::iterating)
        break;
    }
    return states;
  }
} // namespace

int
main()
{
  using test_tools::check;
  CoulombParameters parameters;
  parameters.tolerance         = 1e-6;
  parameters.max_iterations    = 6;
  parameters.divergence_window = 3;

  {
    CoulombFixedPoint fixed_point(parameters);
    const auto        states = run(fixed_point, {1., 0.1, 1e-3, 1e-6, 1e-9});
    check(states.size() == 4 && states.back() == State::converged &&
            fixed_point.message() == "converged" &&
            fixed_point.changes().size() == 4,
          "converges at the first change <= tolerance (4th of 5)",
          states.size());
  }
  {
    // growth in 3 consecutive updates; a decrease resets the count
    CoulombFixedPoint fixed_point(parameters);
    const auto states = run(fixed_point, {0.5, 0.6, 0.4, 0.5, 0.7, 0.9, 1.});
    check(states.size() == 6 && states.back() == State::diverged &&
            fixed_point.message() ==
              "Coulomb fixed point diverged (the change of psi grew in 3 "
              "consecutive iterations)",
          "diverges after 3 consecutive growths (the reset at 0.4 counted)",
          fixed_point.message());
  }
  {
    CoulombFixedPoint fixed_point(parameters);
    const auto states = run(fixed_point, {0.5, 0.4, 0.3, 0.2, 0.1, 0.05, 1.});
    check(states.size() == 6 && states.back() == State::iteration_limit &&
            fixed_point.message() ==
              "Coulomb fixed point: maximum iterations (6) reached, relative "
              "change 0.05",
          "stops at the limit after 6 updates (6 Tresca problems solved)",
          fixed_point.message());
  }
  {
    // non-finite wins over every other test
    CoulombFixedPoint fixed_point(parameters);
    const auto        states =
      run(fixed_point, {0.5, std::numeric_limits<double>::quiet_NaN()});
    check(states.size() == 2 && states.back() == State::not_finite &&
            fixed_point.message() ==
              "Coulomb fixed point: non-finite slip bounds",
          "a NaN change stops the loop as non-finite",
          fixed_point.message());
  }
  {
    // psi unchanged by the first update (e.g. a Tresca solution that is
    // already Coulomb's)
    CoulombFixedPoint fixed_point(parameters);
    const auto        states = run(fixed_point, {0., 0.});
    check(states.size() == 1 && states.back() == State::converged,
          "a zero change converges at once",
          states.size());
  }
  check(CoulombFixedPoint::relative_change(4., 16.) == 0.5 &&
          CoulombFixedPoint::relative_change(4., 0.) == 2. &&
          CoulombFixedPoint::relative_change(0., 0.) == 0.,
        "relative change: sqrt(4/16) = 0.5; psi = 0: absolute sqrt(4) = 2",
        CoulombFixedPoint::relative_change(4., 0.));
  return test_tools::finish();
}
