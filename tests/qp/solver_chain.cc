// The solver chain `auto` (lib/qp/solver_chain.h):
//  - policy: bounds only -> the bounds chain (mprgp first), a disc -> the
//    general chain (mpgp-bb first), equality -> SMALSE-M around each;
//  - fall-back: on a planted bound QP with an iteration limit that MPRGP
//    cannot meet, attempt 1 (mprgp) ends with max_iterations and attempt 2
//    (mpgp-bb, warm started) converges; the record lists both attempts
//    (solver, reason, iterations), sums the work, is converged, and the
//    returned x has KKT residuals (recomputed here) below tol ||b|| and
//    equals the planted x*;
//  - cold start (Auto/Warm start = false) with the same limit: the
//    fall-back starts from x0 and needs more iterations than warm;
//  - every solver fails (limit 2): three attempts, all max_iterations,
//    reported not converged, chosen = the last, message says so;
//  - JSON holds the attempts and the chosen solver;
//  - bad chains are rejected naming the parameter.
#include "planted_problems.h"

#include <qp/kkt_residuals.h>
#include <qp/problem_io.h>
#include <qp/smalse_m.h>
#include <qp/solver_chain.h>
#include <qp/solver_factory.h>

#include <nlohmann/json.hpp>

#include <tuple>

using namespace qptest;
using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

namespace
{
  double
  l2(const std::vector<double> &v)
  {
    double s = 0.;
    for (const double x : v)
      s += x * x;
    return std::sqrt(s);
  }
} // namespace

int
main()
{
  Checker check;

  // a bound QP that MPRGP solves in a few dozen iterations (kappa 1e3)
  const Planted      P = make_planted({BlockType::bound}, 60, 20, 5, 1e3);
  const unsigned int n = P.x_star.size();
  Vec                layout(n);
  const auto         problem = make_problem(P.A, P.b, P.blocks, layout);
  const double       tol     = 1e-10;

  // how many iterations MPRGP alone needs
  unsigned int mprgp_iterations = 0;
  {
    SolverParameters prm;
    prm.tolerance = tol;
    Vec        x(n);
    const auto s     = create<Vec>("mprgp", prm)->solve(problem, x);
    mprgp_iterations = s.iterations;
    check.check(s.converged() && s.iterations >= 10,
                "mprgp alone converges in " + std::to_string(s.iterations) +
                  " iterations (>= 10, so a limit can stop it)");
  }

  // the fall-back case: the limit is 60 % of what MPRGP needs
  const unsigned int limit                     = (6 * mprgp_iterations) / 10;
  unsigned int       warm_fall_back_iterations = 0;
  {
    SolverParameters prm;
    prm.tolerance      = tol;
    prm.max_iterations = limit;
    SolverChain<Vec> chain(prm);
    check.check(chain.chain(problem) ==
                  std::vector<std::string>{"mprgp", "mpgp-bb", "spg-qp"},
                "bounds only: chain mprgp, mpgp-bb, spg-qp");
    Vec        x(n);
    const auto s = chain.solve(problem, x);
    const bool two =
      s.attempts.size() == 2 && s.attempts[0].solver == "mprgp" &&
      s.attempts[0].reason == ConvergenceReason::max_iterations &&
      s.attempts[0].iterations == limit && !s.attempts[0].converged() &&
      s.attempts[1].solver == "mpgp-bb" && s.attempts[1].converged();
    check.check(two,
                "limit " + std::to_string(limit) +
                  ": attempt 1 mprgp max_iterations, attempt 2 mpgp-bb "
                  "converged (" +
                  std::to_string(s.attempts.size()) + " attempts)");
    if (two)
      warm_fall_back_iterations = s.attempts[1].iterations;
    check.check(s.converged() && s.solver == "auto" && s.chosen_attempt == 1 &&
                  s.iterations ==
                    s.attempts[0].iterations + s.attempts[1].iterations &&
                  s.n_hessian_products == s.attempts[0].n_hessian_products +
                                            s.attempts[1].n_hessian_products,
                "record: converged, chosen attempt 2, work summed (" +
                  std::to_string(s.iterations) + " iterations)");
    {
      // the history runs through both attempts, stamped monotonically
      const std::size_t h0       = s.attempts[0].history.size();
      bool              monotone = s.history_time.size() == s.history.size() &&
                      s.history_iterations.size() == s.history.size() &&
                      s.history_products.size() == s.history.size();
      for (std::size_t i = 1; monotone && i < s.history.size(); ++i)
        monotone = s.history_time[i] >= s.history_time[i - 1] &&
                   s.history_iterations[i] >= s.history_iterations[i - 1] &&
                   s.history_products[i] >= s.history_products[i - 1];
      check.check(
        s.attempts.size() == 2 &&
          s.history.size() == h0 + s.attempts[1].history.size() && monotone &&
          s.history_iterations.back() == s.iterations &&
          s.history_products.back() <= s.n_hessian_products &&
          s.history.back() == s.attempts[1].history.back() &&
          s.history.back() == s.final_criterion,
        "history: both attempts (" + std::to_string(s.history.size()) +
          " entries), stamps nondecreasing, ends at the total iterations and "
          "the final criterion");
    }
    const KKTResiduals kkt = compute_kkt_residuals(problem, x);
    check.check(kkt.stationarity <= 10 * tol * s.norm_b &&
                  kkt.feasibility <= 1e-14 &&
                  kkt.complementarity <= 10 * tol * s.norm_b &&
                  s.kkt.stationarity <= 10 * tol * s.norm_b,
                "KKT of the returned x: stationarity " +
                  sci(kkt.stationarity / s.norm_b) + " ||b||, feasibility " +
                  sci(kkt.feasibility) + ", complementarity " +
                  sci(kkt.complementarity / s.norm_b) + " ||b||");
    check.check(distance(x, P.x_star) <= 1e-7 * (1 + l2(P.x_star)),
                "x = planted x* (error " + sci(distance(x, P.x_star)) + ")");
    const auto j = nlohmann::json::parse(s.to_json(false));
    check.check(j["attempts"].size() == 2 &&
                  j["attempts"][0]["reason"] == "max_iterations" &&
                  j["attempts"][1]["reason"] == "converged" &&
                  j["chosen_solver"] == "mpgp-bb" && j["converged"] == true,
                "JSON: attempts with reasons, chosen_solver mpgp-bb");
  }

  // cold start: the fall-back begins at x0 again
  {
    SolverParameters prm;
    prm.tolerance             = tol;
    prm.max_iterations        = limit;
    prm.auto_chain.warm_start = false;
    Vec        x(n);
    const auto s = SolverChain<Vec>(prm).solve(problem, x);
    check.check(s.attempts.size() >= 2 &&
                  s.attempts[1].iterations > warm_fall_back_iterations,
                "cold start: attempt 2 needs " +
                  (s.attempts.size() >= 2 ?
                     std::to_string(s.attempts[1].iterations) :
                     std::string("-")) +
                  " iterations, more than warm (" +
                  std::to_string(warm_fall_back_iterations) + ")");
  }

  // every solver fails
  {
    SolverParameters prm;
    prm.tolerance      = tol;
    prm.max_iterations = 2;
    Vec        x(n);
    const auto s   = create<Vec>("auto", prm)->solve(problem, x);
    bool       all = s.attempts.size() == 3;
    for (const auto &a : s.attempts)
      all =
        all && a.reason == ConvergenceReason::max_iterations && !a.converged();
    check.check(all && !s.converged() &&
                  s.reason == ConvergenceReason::max_iterations &&
                  s.chosen_attempt == 2 &&
                  s.message.find("every solver of the chain failed") !=
                    std::string::npos,
                "limit 2: three attempts, all max_iterations, not converged "
                "(" +
                  s.message + ")");
  }

  // general sets: mpgp-bb first, no fall-back needed
  {
    const Planted Q =
      make_planted({BlockType::disc, BlockType::bound}, 20, 4, 7);
    Vec              l(Q.x_star.size()), x(Q.x_star.size());
    const auto       pq = make_problem(Q.A, Q.b, Q.blocks, l);
    SolverParameters prm;
    prm.tolerance = tol;
    SolverChain<Vec> chain(prm);
    const auto       s = chain.solve(pq, x);
    check.check(chain.chain(pq) ==
                    std::vector<std::string>{"mpgp-bb", "mpgp", "spg-qp"} &&
                  s.attempts.size() == 1 && s.attempts[0].solver == "mpgp-bb" &&
                  s.converged() &&
                  distance(x, Q.x_star) <= 1e-7 * (1 + l2(Q.x_star)),
                "disc + bound: mpgp-bb first, converged at once, x = x*");
  }

  // equality constraints: SMALSE-M around the chain's solvers; the sum of
  // x equals that of x* (a constraint x* satisfies)
  {
    auto eq   = std::make_shared<EqualityConstraints<Vec>>();
    eq->vmult = [](Vec &dst, const Vec &src)
    {
      dst.reinit(1);
      dst[0] = src.mean_value() * src.size();
    };
    eq->Tvmult = [n](Vec &dst, const Vec &src)
    {
      dst.reinit(n);
      dst = src[0];
    };
    eq->c.reinit(1);
    for (const double v : P.x_star)
      eq->c[0] += v;
    eq->n_constraints = 1;
    eq->norm_sq       = n;
    auto with_eq      = problem;
    with_eq.equality  = eq;
    SolverParameters prm;
    prm.tolerance = 1e-9;
    SolverChain<Vec> chain(prm);
    Vec              x(n);
    const auto       s = chain.solve(with_eq, x);
    check.check(s.attempts.size() >= 1 &&
                  s.attempts[0].solver == "smalse-m(mprgp)" && s.converged() &&
                  chain.equality_residual() <= 1e-9 * s.norm_b &&
                  distance(x, P.x_star) <= 1e-6 * (1 + l2(P.x_star)),
                "equality: attempt 1 smalse-m(mprgp), converged, "
                "||Bx - c|| = " +
                  sci(chain.equality_residual()) + ", x = x*");
  }

  // bad chains
  for (const auto &[chain, general, piece] :
       std::vector<std::tuple<std::string, bool, std::string>>{
         {"mprgp, nosuch", false, "nosuch"},
         {"auto", false, "auto"},
         {"mpgp, mprgp", true, "bound and box"},
         {" , ", false, "empty"}})
  {
    SolverParameters prm;
    (general ? prm.auto_chain.general : prm.auto_chain.bounds) = chain;
    std::string what;
    try
    {
      prm.check();
    }
    catch (const std::exception &e)
    {
      what = plain_message(e);
    }
    check.check(what.find(piece) != std::string::npos &&
                  what.find(general ? "QP solver/Auto/Chain for general sets" :
                                      "QP solver/Auto/Chain for bounds") !=
                    std::string::npos,
                "chain '" + chain + "' rejected naming the parameter");
  }
  return check.finish("solver_chain");
}
