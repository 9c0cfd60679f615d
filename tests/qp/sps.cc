// Symmetric positive SEMIdefinite Hessians (MPRGPS, thesis 2.4.5): A is the
// 1D Neumann Laplacian (kernel: the constants).  With x >= 0 the cost
// 1/2 x'Ax - b'x is bounded below iff b'1 <= 0.
//  - b'1 < 0: solvable; mprgp (and the MPGP family) must converge with
//    small KKT residuals;
//  - b'1 > 0: unbounded; mprgp must stop with reason `unbounded` (its
//    solvability test: alpha_cg = alpha_f = infinity), never `converged`;
//  - box constraints on the same A: always solvable, must converge.
// Also random SPS matrices with a 3-dimensional kernel and planted
// solvable data (b = A x* + multipliers of active bounds).
#include "planted_problems.h"

#include <qp/solver_factory.h>

using namespace qptest;
using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

namespace
{
  Dense
  neumann_laplacian(const unsigned n)
  {
    Dense A;
    A.n = n;
    A.a.assign(n * n, 0.);
    for (unsigned i = 0; i + 1 < n; ++i)
    {
      A.a[i * n + i] += 1.;
      A.a[(i + 1) * n + i + 1] += 1.;
      A.a[i * n + i + 1] -= 1.;
      A.a[(i + 1) * n + i] -= 1.;
    }
    return A;
  }
} // namespace

int
main()
{
  Checker                          check;
  const unsigned int               n = 30;
  const Dense                      A = neumann_laplacian(n);
  std::mt19937                     rng(7);
  std::normal_distribution<double> normal;

  std::vector<Block> bounds, boxes;
  for (unsigned i = 0; i < n; ++i)
  {
    bounds.push_back({BlockType::bound, i, 0.});
    boxes.push_back({BlockType::box, i, -1., 1.});
  }
  std::vector<double> b(n);
  for (double &v : b)
    v = normal(rng);
  double sum = 0.;
  for (const double v : b)
    sum += v;
  std::vector<double> b_solvable(b), b_unbounded(b);
  for (unsigned i = 0; i < n; ++i)
  {
    b_solvable[i] -= (sum + 1.) / n;  // b'1 = -1
    b_unbounded[i] -= (sum - 1.) / n; // b'1 = +1
  }

  for (const std::string solver : {"mprgp", "mpgp", "mpgp-bb", "mwpgp"})
  {
    SolverParameters prm;
    prm.tolerance      = 1e-10;
    prm.max_iterations = 20000;
    Vec layout(n);
    {
      auto       problem = make_problem(A, b_solvable, bounds, layout);
      Vec        x(n);
      const auto s = create<Vec>(solver, prm)->solve(problem, x);
      check.check(s.converged() && s.kkt.stationarity <= 1e-9 * s.norm_b &&
                    s.kkt.complementarity <= 1e-8 * s.norm_b,
                  solver +
                    ", bound, b'1 < 0 (solvable): " + to_string(s.reason) +
                    " in " + std::to_string(s.iterations) +
                    " iterations, KKT " + sci(s.kkt.stationarity) + " / " +
                    sci(s.kkt.complementarity));
    }
    {
      auto       problem = make_problem(A, b_unbounded, bounds, layout);
      Vec        x(n);
      const auto s = create<Vec>(solver, prm)->solve(problem, x);
      check.check(s.reason == ConvergenceReason::unbounded && !s.converged(),
                  solver + ", bound, b'1 > 0 (unbounded): reported " +
                    to_string(s.reason) + " after " +
                    std::to_string(s.iterations) + " iterations");
    }
    {
      auto       problem = make_problem(A, b_unbounded, boxes, layout);
      Vec        x(n);
      const auto s = create<Vec>(solver, prm)->solve(problem, x);
      check.check(s.converged() && s.kkt.stationarity <= 1e-9 * s.norm_b,
                  solver + ", box (always solvable): " + to_string(s.reason) +
                    " in " + std::to_string(s.iterations) + " iterations");
    }
    // random SPS, kernel of dimension 3, planted solvable data
    for (unsigned seed = 1; seed <= 3; ++seed)
    {
      std::mt19937                           r2(seed);
      const Dense                            As = random_spd(n, 0., 10., r2, 3);
      std::vector<double>                    xs(n), bs(n);
      std::vector<Block>                     blks;
      std::uniform_real_distribution<double> u(0., 1.);
      for (unsigned i = 0; i < n; ++i)
      {
        blks.push_back({BlockType::bound, i, 0.});
        xs[i] = u(r2) < 0.5 ? 0. : u(r2);
      }
      As.vmult(bs.data(), xs.data());
      for (unsigned i = 0; i < n; ++i)
        if (xs[i] == 0.)
          bs[i] -= 0.5 + u(r2); // multiplier: g_i = mu_i > 0
      auto       problem = make_problem(As, bs, blks, layout);
      Vec        x(n);
      const auto s = create<Vec>(solver, prm)->solve(problem, x);
      check.check(s.converged() && s.kkt.stationarity <= 1e-9 * s.norm_b,
                  solver + ", random SPS (kernel 3), seed " +
                    std::to_string(seed) + ": " + to_string(s.reason) + " in " +
                    std::to_string(s.iterations) + " iterations");
    }
  }
  return check.finish("sps");
}
