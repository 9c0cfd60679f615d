// Every core solver (mprgp, mpgp, mpgp-bb, mwpgp; cgc on bounds and boxes) on
// every set type it
// accepts (bound, box, disc, ellipse, cone, a mix), on random strictly
// convex QPs with a planted solution: x*, the active blocks and positive
// multipliers are chosen, b = A x* + sum mu_j n_j(x*).  Solved from x0 = 0
// to ||g^P|| <= 1e-10 ||b||; checks: converged, ||x - x*|| <= 1e-8 (1 +
// ||x*||), KKT residuals small, statistics consistent (iterations = sum of
// kinds, products counted); MPRGP, MPGP and MPGP-BB also with the
// projected-CG expansion (parameter `expansion`).  Then ellipses with axis
// ratios up to 1e4 under each of the three stopping criteria.
#include "planted_problems.h"

#include <qp/solver_factory.h>

#include <iomanip>

using namespace qptest;
using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

/// The checks every solve of a planted problem must pass: converged, x*
/// found, KKT residuals small.
void
check_planted_solution(Checker                &check,
                       const std::string      &tag,
                       const SolverStatistics &stats,
                       const Planted          &P,
                       const Vec              &x)
{
  const double err = distance(x, P.x_star);
  check.check(stats.converged(),
              tag + "converged (" + to_string(stats.reason) + ")");
  check.check(err <= 1e-8 * (1. + norm(P.x_star)),
              tag + "||x - x*|| = " + sci(err));
  check.check(stats.kkt.stationarity <= 1e-9 * stats.norm_b &&
                stats.kkt.feasibility <= 1e-12 &&
                stats.kkt.complementarity <= 1e-8 * stats.norm_b,
              tag + "KKT " + sci(stats.kkt.stationarity) + " " +
                sci(stats.kkt.feasibility) + " " +
                sci(stats.kkt.complementarity));
}

/// @p solver with @p prm on the planted problem @p P from x = 0.
SolverStatistics
solve_planted(const std::string      &solver,
              const SolverParameters &prm,
              const Planted          &P,
              Vec                    &x)
{
  Vec  layout(P.x_star.size());
  auto problem = make_problem(P.A, P.b, P.blocks, layout);
  x.reinit(P.x_star.size());
  return create<Vec>(solver, prm)->solve(problem, x);
}

int
main()
{
  Checker check;
  struct Case
  {
    std::string            name;
    std::vector<BlockType> types;
  };
  const std::vector<Case> all_sets   = {{"bound", {BlockType::bound}},
                                        {"box", {BlockType::box}},
                                        {"disc", {BlockType::disc}},
                                        {"ellipse", {BlockType::ellipse}},
                                        {"cone", {BlockType::cone}},
                                        {"mixed",
                                         {BlockType::bound,
                                          BlockType::box,
                                          BlockType::disc,
                                          BlockType::ellipse,
                                          BlockType::cone}}};
  const std::vector<Case> bound_sets = {all_sets[0],
                                        all_sets[1],
                                        {"bound+box",
                                         {BlockType::bound, BlockType::box}}};

  std::cout << std::setw(8) << "solver" << std::setw(10) << "set"
            << std::setw(6) << "seed" << std::setw(5) << "n" << std::setw(7)
            << "active" << std::setw(7) << "iter" << std::setw(6) << "cg"
            << std::setw(6) << "half" << std::setw(6) << "exp" << std::setw(6)
            << "prop" << std::setw(6) << "A*x" << std::setw(11) << "|x-x*|"
            << std::setw(11) << "crit" << std::endl;
  // projected-CG expansions: accepted ones (half-steps without a
  // fall-back to alpha_bar), so that the test exercises them
  unsigned int n_projected_cg = 0;
  // "name/expansion": MPRGP, MPGP and MPGP-BB also with the projected-CG
  // expansion
  for (const std::string config : {"mprgp",
                                   "mprgp/projected-cg",
                                   "mpgp",
                                   "mpgp/projected-cg",
                                   "mpgp-bb",
                                   "mpgp-bb/projected-cg",
                                   "mwpgp"})
    for (const Case &c :
         (config.rfind("mprgp", 0) == 0 ? bound_sets : all_sets))
      for (const unsigned int seed : {1u, 2u, 3u})
      {
        const std::string  solver = config.substr(0, config.find('/'));
        const Planted      P = make_planted(c.types, 30, 8, 100 * seed + 7);
        const unsigned int n = P.x_star.size();
        SolverParameters   prm;
        prm.tolerance      = 1e-10;
        prm.max_iterations = 5000;
        if (config.find('/') != std::string::npos)
          prm.expansion = config.substr(config.find('/') + 1);
        Vec            x;
        const auto     stats = solve_planted(solver, prm, P, x);
        const double   err   = distance(x, P.x_star);
        const unsigned kinds = stats.n_cg + stats.n_half_steps +
                               stats.n_proportioning +
                               (stats.n_expansions - stats.n_half_steps);
        std::cout << std::setw(8) << config << std::setw(10) << c.name
                  << std::setw(6) << seed << std::setw(5) << n << std::setw(7)
                  << P.n_active << std::setw(7) << stats.iterations
                  << std::setw(6) << stats.n_cg << std::setw(6)
                  << stats.n_half_steps << std::setw(6) << stats.n_expansions
                  << std::setw(6) << stats.n_proportioning << std::setw(6)
                  << stats.n_hessian_products << std::setw(11) << sci(err)
                  << std::setw(11) << sci(stats.final_criterion) << "  "
                  << to_string(stats.reason) << std::endl;
        const std::string tag =
          config + "/" + c.name + "/" + std::to_string(seed) + ": ";
        // (MPGP-BB's n_fall_back also counts its rejected BB steps)
        if (prm.expansion == "projected-cg" && solver != "mpgp-bb")
          n_projected_cg += stats.n_half_steps - stats.n_fall_back;
        check.verbose = false;
        check_planted_solution(check, tag, stats, P, x);
        check.check(kinds == stats.iterations &&
                      stats.n_hessian_products >= stats.iterations &&
                      stats.history.size() == stats.iterations + 1 &&
                      history_consistent(stats) &&
                      stats.history_iterations.back() == stats.iterations,
                    tag + "statistics consistent (history with time "
                          "stamps and counts)");
      }
  // the report's CGC as a registered solver (bounds and boxes as rows of
  // one entry): the same planted solutions
  for (const Case &c : bound_sets)
    for (const unsigned int seed : {1u, 2u, 3u})
    {
      const Planted    P = make_planted(c.types, 30, 8, 100 * seed + 7);
      SolverParameters prm;
      prm.tolerance      = 1e-10;
      prm.max_iterations = 5000;
      Vec               x;
      const auto        stats = solve_planted("cgc", prm, P, x);
      const std::string tag =
        "cgc/" + c.name + "/" + std::to_string(seed) + ": ";
      check.check(stats.solver == "cgc", tag + "solved by cgc");
      check_planted_solution(check, tag, stats, P, x);
    }
  check.verbose = true;
  check.check(n_projected_cg >= 10,
              std::to_string(n_projected_cg) +
                " projected-CG expansions accepted");
  // strongly curved sets: ellipses with axis ratios up to 1e4, under each
  // stopping criterion (the reduced ones are what MwPGP is made for)
  check.verbose = true;
  for (const std::string solver : {"mpgp", "mpgp-bb", "mwpgp"})
    for (const StoppingCriterion criterion :
         {StoppingCriterion::projected,
          StoppingCriterion::reduced,
          StoppingCriterion::reduced_projected})
    {
      const Planted P = make_planted({BlockType::ellipse}, 30, 4, 5, 10., 1e4);
      SolverParameters prm;
      prm.tolerance          = 1e-10;
      prm.stopping_criterion = criterion;
      Vec          x;
      const auto   stats = solve_planted(solver, prm, P, x);
      const double err   = distance(x, P.x_star);
      check.check(stats.converged() && err <= 1e-8 * (1. + norm(P.x_star)),
                  solver + ", ellipses with axis ratio up to 1e4, " +
                    stopping_criterion_names.name(criterion) +
                    " criterion: " + to_string(stats.reason) + " in " +
                    std::to_string(stats.iterations) +
                    " iterations, |x - x*| = " + sci(err));
    }
  return check.finish("solvers_planted");
}
