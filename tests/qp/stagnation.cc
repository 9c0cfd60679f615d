// The stagnation test (SolverBase::check_stop): progress is a new minimum
// of the criterion, or, for the solvers that pass a cost (the active-set
// solvers, SPG-QP, PBBf), a new least cost by more than a relative 1e-12.
//  1. Real progress is not stagnation: MPRGP and SPG-QP on the
//     membrane of benchmark B4 (h = 60) without a stagnation test; their
//     criterion stays above its best for a stretch of L iterations while
//     the cost falls.  With a window of L/2 (which a criterion-only test
//     would trip over) the solve must still converge, in the same number
//     of iterations.
//  2. Real stagnation is still reported: a planted QP solved to machine
//     precision with an unreachable tolerance 1e-30 stops with
//     `stagnation` (not converged, not the iteration limit) for MPRGP,
//     MPGP, MPGP-BB, MwPGP, SPG-QP and PBBf, at the solution.
#include "planted_problems.h"

#include <qp/membrane_generator.h>
#include <qp/solver_factory.h>

#include <algorithm>

using namespace qptest;
using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

int
main()
{
  Checker check;

  // 1. the membrane
  {
    MembraneGenerator::Parameters mp;
    mp.h                    = 60;
    mp.p                    = 0.5;
    const auto         data = MembraneGenerator(mp).generate();
    const unsigned int n    = data->size();
    Problem<Vec>       problem;
    problem.hessian = [&](Vec &dst, const Vec &src)
    { data->hessian.vmult(dst, src); };
    problem.b = data->rhs;
    auto set  = std::make_shared<SeparableSet<Vec>>();
    for (unsigned int i = 0; i < n; ++i)
      set->add_bound(i, data->constraints[0].lower[i]);
    set->finalize(problem.b);
    problem.constraints = set;
    problem.lambda_max =
      MembraneGenerator(mp).exact_extreme_eigenvalues().second;

    // measured longest stretches: mprgp 22, spg-qp 13 iterations.  (PBBf
    // is not here: its non-monotone BB phase may run K = 10 steps
    // without a new least cost before its fall-back, so a window below
    // K may stop it; the default window is 1000.)
    for (const auto &[solver, stretch] :
         std::vector<std::pair<std::string, unsigned int>>{{"mprgp", 20},
                                                           {"spg-qp", 10}})
    {
      SolverParameters prm;
      prm.tolerance         = 1e-6;
      prm.max_iterations    = 20000;
      prm.stagnation_window = 0;
      Vec        x(n);
      const auto free_run = create<Vec>(solver, prm)->solve(problem, x);
      // longest stretch without a new minimum of the criterion
      unsigned int longest = 0, last = 0;
      double       best = std::numeric_limits<double>::infinity();
      for (unsigned int k = 0; k < free_run.history.size(); ++k)
        if (free_run.history[k] < best)
        {
          best    = free_run.history[k];
          longest = std::max(longest, k - last);
          last    = k;
        }
      check.check(free_run.converged() && longest >= stretch,
                  "membrane h = 60, " + solver +
                    ", no stagnation test: " + to_string(free_run.reason) +
                    " in " + std::to_string(free_run.iterations) +
                    " iterations; longest stretch without a new criterion "
                    "minimum: " +
                    std::to_string(longest) + " iterations");

      prm.stagnation_window = longest / 2;
      Vec        y(n);
      const auto windowed = create<Vec>(solver, prm)->solve(problem, y);
      check.check(windowed.converged() &&
                    windowed.iterations == free_run.iterations,
                  solver + " with a stagnation window of " +
                    std::to_string(prm.stagnation_window) + ": " +
                    to_string(windowed.reason) + " in " +
                    std::to_string(windowed.iterations) + " iterations " +
                    windowed.message);
    }
  }

  // 2. real stagnation
  {
    const Planted      P = make_planted({BlockType::bound}, 30, 8, 11, 100.);
    const unsigned int n = P.x_star.size();
    Vec                layout(n);
    const auto         problem = make_problem(P.A, P.b, P.blocks, layout);
    for (const std::string solver :
         {"mprgp", "mpgp", "mpgp-bb", "mwpgp", "spg-qp", "pbbf"})
    {
      SolverParameters prm;
      prm.tolerance         = 1e-30;
      prm.max_iterations    = 20000;
      prm.stagnation_window = 50;
      Vec          x(n);
      const auto   s   = create<Vec>(solver, prm)->solve(problem, x);
      const double err = distance(x, P.x_star);
      check.check(s.reason == ConvergenceReason::stagnation && !s.converged() &&
                    s.iterations < 2000 && err <= 1e-10 * (1. + norm(P.x_star)),
                  solver + ", tolerance 1e-30: " + to_string(s.reason) +
                    " after " + std::to_string(s.iterations) +
                    " iterations, |x - x*| = " + sci(err) + " (" + s.message +
                    ")");
    }
  }
  return check.finish("stagnation");
}
