// CGC (lib/qp/cgc.h) on problems with a known solution:
//  1. bound constraints x >= l, planted solution (random SPD C, chosen
//     active set and positive multipliers), no preconditioner, report's
//     "one at a time" and lemma 7.2's "all negative" release;
//  2. coupled (non-orthogonal) rows a_i'x <= c_i with a planted solution;
//  3. the same with PCG-2 (split diagonal E = D^{1/2}), a symmetric
//     preconditioner (deal.II SSOR) and the loose-then-strict inner
//     tolerance switched off (n_loose = 0);
//  4. an SPS Hessian whose cost is unbounded along a free direction:
//     reason "unbounded";
//  5. an iteration limit of 3: reason "max_iterations", not converged;
//  6. the report's stopping tests (StoppingTest::report): a tight epsilon
//     finds x*, a loose one stops CG earlier by the relative step test.
// Asserts ||x - x*|| <= 1e-8 ||x*||, the criterion <= 1e-10 ||b||, the
// returned multipliers close to the planted ones.
#include "planted_problems.h"

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <qp/cgc.h>

#include <cmath>
#include <iostream>
#include <random>

using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

using qptest::check;
using qptest::uniform;

namespace
{
  std::mt19937 rng(20240521);

  double
  distance(const Vec &a, const Vec &b)
  {
    Vec d(a);
    d -= b;
    return d.l2_norm();
  }
} // namespace

int
main()
{
  const unsigned int           n = 60;
  dealii::SparsityPattern      sp;
  dealii::SparseMatrix<double> A;
  qptest::random_sparse_spd(n, 3, 0.05, rng, sp, A);
  const auto hessian = [&](Vec &dst, const Vec &src) { A.vmult(dst, src); };

  // ---- 1. bounds, planted solution
  for (const auto release :
       {CGC<Vec>::Release::one, CGC<Vec>::Release::all_negative})
  {
    Vec  x_star(n), lower(n), mu(n);
    auto rows = std::make_shared<LinearInequalities>();
    for (unsigned int i = 0; i < n; ++i)
    {
      lower[i] = uniform(rng, -1., 0.);
      if (i % 3 == 0) // active, multiplier > 0
      {
        x_star[i] = lower[i];
        mu[i]     = uniform(rng, 0.1, 1.);
      }
      else
        x_star[i] = lower[i] + uniform(rng, 0.1, 1.);
      rows->add_lower_bound(i, lower[i]);
    }
    // KKT: Cx* - b = mu on the active bounds (g_i = u_i >= 0)
    CGCProblem<Vec> problem;
    problem.hessian = hessian;
    problem.b.reinit(n);
    A.vmult(problem.b, x_star);
    problem.b -= mu;
    problem.constraints = rows;
    CGC<Vec>::AdditionalData data;
    data.tolerance = 1e-10;
    data.release   = release;
    CGC<Vec>          cgc(data);
    Vec               x(n);
    const auto        stats = cgc.solve(problem, x);
    const std::string label =
      release == CGC<Vec>::Release::one ? "one" : "all_negative";
    std::cout << "     bounds/" << label << ": " << stats.iterations
              << " CG steps, " << stats.n_outer << " outer, "
              << stats.n_half_steps << " hits, " << stats.n_proportioning
              << " releases, criterion " << stats.final_criterion << std::endl;
    check(stats.converged(), "bounds (" + label + "): converged");
    check(qptest::history_consistent(stats),
          "bounds (" + label + "): history with time stamps and counts");
    check(distance(x, x_star) <= 1e-8 * x_star.l2_norm(),
          "bounds (" + label + "): ||x - x*|| <= 1e-8 ||x*||");
    double max_mu_error = 0.;
    for (const auto &[row, value] : cgc.multipliers())
      max_mu_error = std::max(max_mu_error, std::abs(value - mu[row]));
    check(cgc.multipliers().size() == n / 3 && max_mu_error < 1e-8,
          "bounds (" + label + "): multipliers = planted ones");
  }

  // ---- 2./3. coupled rows
  const unsigned int m = 12;
  Vec                x_star(n);
  for (unsigned int i = 0; i < n; ++i)
    x_star[i] = uniform(rng, -1., 1.);
  auto                rows = std::make_shared<LinearInequalities>();
  Vec                 sum_ua(n);
  std::vector<double> planted_u(m, 0.);
  for (unsigned int r = 0; r < m; ++r)
  {
    // a row over 5 random unknowns, oriented so that a'x* > 0 (x = 0
    // is then a feasible start)
    std::vector<dealii::types::global_dof_index> cols;
    std::vector<double>                          vals;
    double                                       ax = 0.;
    for (unsigned int k = 0; k < 5; ++k)
    {
      const unsigned int c = rng() % n;
      if (std::find(cols.begin(), cols.end(), c) != cols.end())
        continue;
      cols.push_back(c);
      vals.push_back(uniform(rng, -1., 1.));
      ax += vals.back() * x_star[c];
    }
    if (ax < 0.)
    {
      for (auto &v : vals)
        v = -v;
      ax = -ax;
    }
    const bool active = (r % 2 == 0);
    rows->add_row(cols, vals, active ? ax : ax + uniform(rng, 0.1, 1.));
    if (active)
    {
      planted_u[r] = uniform(rng, 0.1, 1.);
      for (std::size_t k = 0; k < cols.size(); ++k)
        sum_ua[cols[k]] += planted_u[r] * vals[k];
    }
  }
  check(!rows->rows_orthogonal(), "coupled rows are not orthogonal");
  CGCProblem<Vec> coupled;
  coupled.hessian = hessian;
  coupled.b.reinit(n);
  A.vmult(coupled.b, x_star);
  coupled.b += sum_ua; // Cx* - b + A_J'u = 0
  coupled.constraints = rows;

  Vec diagonal(n), sqrt_diag(n);
  for (unsigned int i = 0; i < n; ++i)
    sqrt_diag[i] = std::sqrt(A.diag_element(i));
  dealii::PreconditionSSOR<dealii::SparseMatrix<double>> ssor;
  ssor.initialize(A, 1.2);

  for (const std::string variant :
       {"none", "split-diagonal", "ssor", "strict-only"})
  {
    CGC<Vec>::AdditionalData data;
    data.tolerance = 1e-10;
    if (variant == "strict-only")
      data.n_loose = 0;
    CGC<Vec> cgc(data);
    if (variant == "split-diagonal")
    {
      const auto divide = [&](Vec &dst, const Vec &src)
      {
        for (unsigned int i = 0; i < n; ++i)
          dst[i] = src[i] / sqrt_diag[i];
      };
      cgc.set_split_preconditioner(divide, divide);
    }
    if (variant == "ssor")
      cgc.set_preconditioner([&](Vec &dst, const Vec &src)
                             { ssor.vmult(dst, src); });
    Vec        x(n);
    const auto stats = cgc.solve(coupled, x);
    std::cout << "     coupled/" << variant << ": " << stats.iterations
              << " CG steps, " << stats.n_outer << " outer, criterion "
              << stats.final_criterion << ", " << to_string(stats.reason)
              << ", infeasibility " << stats.kkt.feasibility << ", |J| "
              << cgc.multipliers().size() << ", error " << distance(x, x_star)
              << std::endl;
    check(stats.converged() && distance(x, x_star) <= 1e-8 * x_star.l2_norm(),
          "coupled rows (" + variant + "): converged to x*");
    double max_u_error = 0.;
    for (const auto &[row, value] : cgc.multipliers())
      max_u_error = std::max(max_u_error, std::abs(value - planted_u[row]));
    check(max_u_error < 1e-7,
          "coupled rows (" + variant + "): multipliers = planted ones");
  }

  // ---- 6. the report's stopping tests (remark 7.2) on the coupled rows:
  //         with a tight epsilon they find x*; with epsilon = 1e-2 the
  //         relative step test ||dx|| / max(1, ||x||) < epsilon ends CG
  //         early, so fewer CG steps and a worse x
  {
    std::vector<unsigned int> steps;
    std::vector<double>       errors;
    for (const double epsilon : {1e-24, 1e-2})
    {
      CGC<Vec>::AdditionalData data;
      data.stopping_test = CGC<Vec>::StoppingTest::report;
      data.tolerance     = epsilon;
      data.n_loose       = 0;
      CGC<Vec>   cgc(data);
      Vec        x(n);
      const auto stats = cgc.solve(coupled, x);
      std::cout << "     coupled/report, epsilon " << epsilon << ": "
                << stats.iterations << " CG steps, " << stats.n_outer
                << " outer, criterion " << stats.final_criterion << ", "
                << to_string(stats.reason) << ", error " << distance(x, x_star)
                << std::endl;
      check(stats.reason == ConvergenceReason::converged && stats.converged(),
            std::string("report's tests, epsilon ") +
              (epsilon < 1e-3 ? "1e-24" : "1e-2") +
              ": converged (the record's tolerance is the criterion "
              "reached)");
      steps.push_back(stats.iterations);
      errors.push_back(distance(x, x_star));
    }
    check(errors[0] <= 1e-8 * x_star.l2_norm(),
          "report's tests, epsilon 1e-24: ||x - x*|| <= 1e-8 ||x*||");
    check(steps[1] < steps[0] && errors[1] > 1e3 * errors[0],
          "report's tests, epsilon 1e-2: the step test stops CG earlier");
  }

  // ---- 4. unbounded: C = diag(1, 0), b = (0, 1), only x_0 >= -1
  {
    dealii::FullMatrix<double> C(2, 2);
    C(0, 0) = 1.;
    CGCProblem<Vec> problem;
    problem.hessian = [&](Vec &dst, const Vec &src) { C.vmult(dst, src); };
    problem.b.reinit(2);
    problem.b[1] = 1.;
    auto r       = std::make_shared<LinearInequalities>();
    r->add_lower_bound(0, -1.);
    problem.constraints = r;
    CGC<Vec>   cgc;
    Vec        x(2);
    const auto stats = cgc.solve(problem, x);
    check(stats.reason == ConvergenceReason::unbounded && !stats.converged(),
          "SPS with a free descent direction: reason unbounded");
  }

  // ---- 5. iteration limit
  {
    CGC<Vec>::AdditionalData data;
    data.tolerance      = 1e-12;
    data.max_iterations = 3;
    CGC<Vec>   cgc(data);
    Vec        x(n);
    const auto stats = cgc.solve(coupled, x);
    check(stats.reason == ConvergenceReason::max_iterations &&
            !stats.converged() && stats.iterations == 3,
          "iteration limit 3: reason max_iterations, not converged");
  }

  return qptest::checker().finish("qp/cgc_known_solutions");
}
