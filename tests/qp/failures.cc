// Failed solves are reported as failures, never as "converged":
//  - iteration limit (max 3 iterations on a problem needing ~25):
//    reason max_iterations, converged() false, JSON says so;
//  - unreachable tolerance (products with 1e-9 noise) and a stagnation
//    window of 50: stagnation or max_iterations, never converged (the
//    convergence claim is checked with a true gradient A x - b);
//  - a Hessian product that returns NaN: non_finite;
//  - an indefinite Hessian: breakdown (negative curvature);
//  - invalid input (sizes, MPRGP on a disc, equality constraints) throws.
// Also the statistics record itself: converged() needs reason AND
// criterion, JSON round trip of the main fields.
#include "planted_problems.h"

#include <qp/solver_factory.h>

#include <nlohmann/json.hpp>

#include <limits>

using namespace qptest;
using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

int
main()
{
  Checker            check;
  const Planted      P = make_planted({BlockType::bound}, 30, 8, 11, 100.);
  const unsigned int n = P.x_star.size();
  Vec                layout(n);
  auto               problem = make_problem(P.A, P.b, P.blocks, layout);

  for (const std::string solver : {"mprgp", "mpgp", "mpgp-bb", "mwpgp"})
  {
    {
      SolverParameters prm;
      prm.tolerance      = 1e-10;
      prm.max_iterations = 3;
      Vec        x(n);
      const auto s = create<Vec>(solver, prm)->solve(problem, x);
      const auto j = nlohmann::json::parse(s.to_json());
      check.check(s.reason == ConvergenceReason::max_iterations &&
                    !s.converged() && s.iterations == 3 &&
                    j["converged"] == false && j["reason"] == "max_iterations",
                  solver + ": iteration limit 3 -> " + to_string(s.reason) +
                    ", converged() = " + std::to_string(s.converged()) +
                    ", JSON reason " + j["reason"].get<std::string>());
    }
    {
      // products with 1e-9 relative noise: the criterion cannot fall
      // below ~1e-9, so 1e-13 is unreachable
      auto                             noisy  = problem;
      auto                             good_h = problem.hessian;
      std::mt19937                     noise_rng(3);
      std::normal_distribution<double> noise;
      noisy.hessian = [&](Vec &dst, const Vec &src)
      {
        good_h(dst, src);
        const double scale = 1e-9 * dst.l2_norm() / std::sqrt(1. * n);
        for (unsigned i = 0; i < n; ++i)
          dst[i] += scale * noise(noise_rng);
      };
      SolverParameters prm;
      prm.tolerance         = 1e-13;
      prm.max_iterations    = 3000;
      prm.stagnation_window = 50;
      Vec        x(n);
      const auto s = create<Vec>(solver, prm)->solve(noisy, x);
      check.check((s.reason == ConvergenceReason::stagnation ||
                   s.reason == ConvergenceReason::max_iterations) &&
                    !s.converged() && s.kkt.stationarity > 1e-13 * s.norm_b,
                  solver + ": unreachable tolerance (noisy products) -> " +
                    to_string(s.reason) + " after " +
                    std::to_string(s.iterations) + " iterations, best " +
                    "criterion in the message: " + s.message);
    }
    {
      auto bad    = problem;
      auto good_h = problem.hessian;
      int  calls  = 0;
      bad.hessian = [&](Vec &dst, const Vec &src)
      {
        good_h(dst, src);
        if (++calls > 60) // after the power iteration
          dst[0] = std::numeric_limits<double>::quiet_NaN();
      };
      bad.lambda_max = 0.;
      SolverParameters prm;
      prm.tolerance = 1e-14;
      Vec        x(n);
      const auto s = create<Vec>(solver, prm)->solve(bad, x);
      check.check(s.reason == ConvergenceReason::non_finite && !s.converged(),
                  solver + ": NaN in a product -> " + to_string(s.reason));
    }
    {
      // indefinite: A - 5 I has negative eigenvalues
      Dense Ai = P.A;
      for (unsigned i = 0; i < n; ++i)
        Ai.a[i * n + i] -= 5.;
      auto indefinite       = make_problem(Ai, P.b, P.blocks, layout);
      indefinite.lambda_max = 110.;
      SolverParameters prm;
      Vec              x(n);
      const auto       s = create<Vec>(solver, prm)->solve(indefinite, x);
      check.check(!s.converged() && (s.reason == ConvergenceReason::breakdown ||
                                     s.reason == ConvergenceReason::unbounded),
                  solver + ": indefinite Hessian -> " + to_string(s.reason) +
                    " (" + s.message + ")");
    }
  }

  // invalid input
  {
    SolverParameters prm;
    Vec              x(n + 1);
    bool             thrown = false;
    try
    {
      create<Vec>("mpgp", prm)->solve(problem, x);
    }
    catch (const std::exception &)
    {
      thrown = true;
    }
    check.check(thrown, "x of the wrong size is rejected");
  }
  {
    const Planted Q = make_planted({BlockType::disc}, 5, 2, 3);
    Vec           l(Q.x_star.size()), x(Q.x_star.size());
    auto          pq = make_problem(Q.A, Q.b, Q.blocks, l);
    std::string   what;
    try
    {
      create<Vec>("mprgp", SolverParameters())->solve(pq, x);
    }
    catch (const std::exception &e)
    {
      what = e.what();
    }
    check.check(what.find("only bound and box") != std::string::npos,
                "mprgp refuses a disc set with a clear message");
  }
  {
    std::string what;
    try
    {
      create<Vec>("no-such-solver", SolverParameters());
    }
    catch (const std::exception &e)
    {
      what = e.what();
    }
    check.check(what.find("valid names") != std::string::npos,
                "unknown solver name rejected, listing the valid names");
  }
  {
    SolverStatistics s;
    s.tolerance       = 1e-8;
    s.reason          = ConvergenceReason::converged;
    s.final_criterion = 1e-6;
    check.check(!s.converged(),
                "converged() is false when the criterion exceeds the "
                "tolerance, whatever the reason says");
    s.final_criterion = std::numeric_limits<double>::quiet_NaN();
    check.check(!s.converged(), "converged() is false for a NaN criterion");
    s.final_criterion = 1e-9;
    s.history         = {1., std::numeric_limits<double>::infinity(), 1e-9};
    const auto j      = nlohmann::json::parse(s.to_json());
    check.check(s.converged() && j["converged"] == true &&
                  j["history"].size() == 3 && j["history"][1] == "inf",
                "JSON: converged record, history with inf as a string");
  }
  {
    // the history's time stamps and counts go with every entry; a
    // superseded entry is dropped with them
    SolverStatistics s;
    s.record_criterion(1., 0.);
    s.iterations         = 4;
    s.n_hessian_products = 9;
    s.record_criterion(1e-3, 0.25);
    s.record_criterion(1e-2, 0.5);
    s.drop_last_criterion();
    const auto j = nlohmann::json::parse(s.to_json());
    check.check(
      j["history"].size() == 2 && j["history_time_s"].size() == 2 &&
        j["history_time_s"][1] == 0.25 && j["history_iterations"][1] == 4 &&
        j["history_products"][1] == 9 &&
        nlohmann::json::parse(s.to_json(false)).count("history_time_s") == 0,
      "JSON: history with time stamps, iterations and products");
  }
  return check.finish("failures");
}
