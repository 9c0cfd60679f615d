// SMALSE-M (lib/qp/smalse_m.h) with bound constraints and linear equality
// constraints Bx = c, planted solution: b = A x* + B'nu - g_bound with
// positive bound multipliers on the active bounds, c = B x*.
//  - SPD Hessian, inner solvers mprgp and spg-qp;
//  - SPS Hessian (a graph Laplacian, kernel = constants) made definite on
//    ker B by a row of ones in B, inner solvers mprgp and pbbf.
// Asserts: converged, ||x - x*|| <= 1e-6 max(1, ||x*||), ||Bx - c|| <=
// 1e-8 ||b||, outer iterations >= 1 reported, KKT stationarity and
// complementarity of the Lagrangian small; and that a limit of 3 inner
// iterations is reported as not converged.
#include "planted_problems.h"

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <qp/problem.h>
#include <qp/separable_set.h>
#include <qp/smalse_m.h>

#include <cmath>
#include <iostream>
#include <random>

using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

using qptest::check;
using qptest::uniform;

namespace
{
  std::mt19937 rng(11);
} // namespace

int
main()
{
  const unsigned int n = 40, m = 3;
  for (const bool semidefinite : {false, true})
  {
    // A: ring Laplacian + random chords (+ shift if SPD)
    dealii::FullMatrix<double> A(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (const unsigned int j : {(i + 1) % n, (i + 7) % n})
      {
        const double w = uniform(rng, 0.5, 1.5);
        A(i, i) += w;
        A(j, j) += w;
        A(i, j) -= w;
        A(j, i) -= w;
      }
    if (!semidefinite)
      for (unsigned int i = 0; i < n; ++i)
        A(i, i) += 0.5;
    dealii::FullMatrix<double> B(m, n);
    for (unsigned int i = 0; i < n; ++i)
    {
      B(0, i) = 1.; // total "momentum": makes A + rho B'B definite
      B(1, i) = uniform(rng, -1., 1.);
      B(2, i) = (i % 5 == 0) ? uniform(rng, -1., 1.) : 0.;
    }
    Vec  x_star(n), g_bound(n), nu(m);
    auto set = std::make_shared<SeparableSet<Vec>>();
    for (unsigned int i = 0; i < n; ++i)
    {
      const double l = uniform(rng, -1., 0.);
      if (i % 2 == 0)
      {
        set->add_bound(i, l);
        if (i % 4 == 0)
        {
          x_star[i]  = l;
          g_bound[i] = uniform(rng, 0.5, 1.5);
        }
        else
          x_star[i] = l + uniform(rng, 0.2, 1.);
      }
      else
        x_star[i] = uniform(rng, -1., 1.);
    }
    set->finalize(x_star);
    for (unsigned int k = 0; k < m; ++k)
      nu[k] = uniform(rng, -1., 1.);

    Problem<Vec> problem;
    problem.hessian = [&](Vec &dst, const Vec &src) { A.vmult(dst, src); };
    problem.b.reinit(n);
    A.vmult(problem.b, x_star);
    Vec Btnu(n);
    B.Tvmult(Btnu, nu);
    problem.b += Btnu;
    problem.b -= g_bound;
    problem.constraints  = set;
    problem.semidefinite = semidefinite;
    auto eq              = std::make_shared<EqualityConstraints<Vec>>();
    eq->vmult            = [&](Vec &dst, const Vec &src) { B.vmult(dst, src); };
    eq->Tvmult = [&](Vec &dst, const Vec &src) { B.Tvmult(dst, src); };
    eq->c.reinit(m);
    B.vmult(eq->c, x_star);
    eq->n_constraints = m;
    problem.equality  = eq;

    const std::string kind = semidefinite ? "SPS" : "SPD";
    for (const std::string &inner :
         semidefinite ? std::vector<std::string>{"mprgp", "pbbf"} :
                        std::vector<std::string>{"mprgp", "spg-qp"})
    {
      SolverParameters prm;
      prm.solver         = inner;
      prm.tolerance      = 1e-10;
      prm.max_iterations = 100000;
      SMALSEM<Vec> smalse(prm);
      Vec          x(n);
      const auto   stats = smalse.solve(problem, x);
      Vec          error(x);
      error -= x_star;
      std::cout << "     " << kind << " / " << inner << ": " << stats.n_outer
                << " outer, " << stats.iterations << " inner iterations, "
                << stats.n_hessian_products << " products, ||x - x*|| "
                << error.l2_norm() << ", ||Bx - c|| "
                << smalse.equality_residual() << ", " << to_string(stats.reason)
                << std::endl;
      check(stats.converged() && stats.n_outer >= 1 &&
              error.l2_norm() <= 1e-6 * std::max(1., x_star.l2_norm()) &&
              smalse.equality_residual() <= 1e-8 * stats.norm_b,
            "SMALSE-M " + kind + " / " + inner + ": converged to x*, Bx = c");
      // one history entry per outer iteration, with time stamps and counts
      check(qptest::history_consistent(stats, false) &&
              stats.history.size() == stats.n_outer &&
              stats.history_iterations.back() == stats.iterations,
            "SMALSE-M " + kind + " / " + inner +
              ": history per outer iteration with time stamps and counts");
      // KKT residuals of the Lagrangian (stationarity, complementarity with
      // the multiplier estimates from Ax - b + B'lambda): small at x*
      check(stats.kkt.stationarity <= 1e-8 * stats.norm_b &&
              stats.kkt.complementarity <= 1e-8 * stats.norm_b,
            "SMALSE-M " + kind + " / " + inner + ": KKT stationarity " +
              std::to_string(stats.kkt.stationarity) + ", complementarity " +
              std::to_string(stats.kkt.complementarity));
      Vec mult_error(smalse.multipliers());
      mult_error -= nu;
      check(mult_error.l2_norm() <= 1e-5 * std::max(1., nu.l2_norm()),
            "SMALSE-M " + kind + " / " + inner +
              ": equality multipliers = planted nu");

      prm.max_iterations = 3;
      SMALSEM<Vec> limited(prm);
      Vec          y(n);
      const auto   s = limited.solve(problem, y);
      check(!s.converged() && s.reason == ConvergenceReason::max_iterations,
            "SMALSE-M " + kind + " / " + inner +
              ": 3 iterations reported as max_iterations");
    }
  }
  return qptest::checker().finish("qp/smalse_planted");
}
