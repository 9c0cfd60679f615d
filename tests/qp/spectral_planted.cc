// SPG-QP, PBBf and APGD (and, through the factory, every solver name they
// are registered under) on random strictly convex QPs with a planted
// solution, for every set type (bound, box, disc, ellipse with rotation and
// axis ratio 20, second-order cone) and for a product of all of them with
// free unknowns:  pick x*, choose active blocks with positive multipliers
// mu_j, set b = A x* + sum_j mu_j n_j (n_j the outward unit normal), so x*
// is the unique solution.  Asserts: reason converged at tolerance 1e-10,
// ||x - x*|| <= 1e-8 max(1, ||x*||), the KKT residuals small; and with an
// iteration limit of 5 the reason is max_iterations and converged() false.
#include "planted_problems.h"

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <qp/problem.h>
#include <qp/separable_set.h>
#include <qp/solver_factory.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <random>

using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

using qptest::check;
using qptest::uniform;

namespace
{
  std::mt19937 rng(7);

  struct Planted
  {
    std::shared_ptr<SeparableSet<Vec>> set =
      std::make_shared<SeparableSet<Vec>>();
    Vec          x_star, g_star; // g* = A x* - b = -sum mu_j n_j
    unsigned int n_active = 0;
  };

  /// Blocks of one type (or all types cyclically for "mixed") over
  /// unknowns [0, n), every other block active; unknowns that do not fill
  /// a block stay free.
  Planted
  plant(const std::string &type, const unsigned int n)
  {
    Planted p;
    p.x_star.reinit(n);
    p.g_star.reinit(n);
    const std::vector<std::string> cycle =
      type == "mixed" ?
        std::vector<std::string>{"bound", "box", "disc", "ellipse", "cone"} :
        std::vector<std::string>{type};
    unsigned int i = 0, block = 0;
    while (true)
    {
      const std::string  t    = cycle[block % cycle.size()];
      const unsigned int size = (t == "disc" || t == "ellipse") ? 2 :
                                t == "cone"                     ? 3 :
                                                                  1;
      if (i + size > n - 2) // keep two free unknowns at the end
        break;
      const bool   active = (block % 2 == 0);
      const double mu     = uniform(rng, 0.5, 2.);
      if (t == "bound")
      {
        const double l = uniform(rng, -1., 0.);
        p.set->add_bound(i, l);
        p.x_star[i] = active ? l : l + uniform(rng, 0.2, 1.);
        if (active)
          p.g_star[i] = mu; // n = -e_i
      }
      else if (t == "box")
      {
        const double l = uniform(rng, -1., -0.5), u = uniform(rng, 0.5, 1.);
        p.set->add_box(i, l, u);
        const bool at_upper = (block % 4 == 0);
        p.x_star[i]         = !active  ? uniform(rng, l + 0.1, u - 0.1) :
                              at_upper ? u :
                                         l;
        if (active)
          p.g_star[i] = at_upper ? -mu : mu;
      }
      else if (t == "disc")
      {
        const double r = uniform(rng, 0.5, 2.), angle = uniform(rng, 0., 6.28);
        p.set->add_disc(i, r);
        const double s  = active ? 1. : uniform(rng, 0.1, 0.8);
        p.x_star[i]     = s * r * std::cos(angle);
        p.x_star[i + 1] = s * r * std::sin(angle);
        if (active)
        {
          p.g_star[i]     = -mu * std::cos(angle);
          p.g_star[i + 1] = -mu * std::sin(angle);
        }
      }
      else if (t == "ellipse")
      {
        const double a = uniform(rng, 1., 2.), b = a / 20.,
                     phi = uniform(rng, 0., 3.14), t_ = uniform(rng, 0., 6.28);
        p.set->add_ellipse(i, a, b, phi);
        const double s  = active ? 1. : uniform(rng, 0.1, 0.8);
        const double y1 = s * a * std::cos(t_), y2 = s * b * std::sin(t_);
        // outward normal in the ellipse frame, then rotated
        double       n1 = std::cos(t_) / a, n2 = std::sin(t_) / b;
        const double nn = std::hypot(n1, n2);
        n1 /= nn;
        n2 /= nn;
        const double c = std::cos(phi), sn = std::sin(phi);
        p.x_star[i]     = c * y1 - sn * y2;
        p.x_star[i + 1] = sn * y1 + c * y2;
        if (active)
        {
          p.g_star[i]     = -mu * (c * n1 - sn * n2);
          p.g_star[i + 1] = -mu * (sn * n1 + c * n2);
        }
      }
      else // cone ||x_t|| <= m x_n
      {
        const double m = uniform(rng, 0.2, 1.), s = uniform(rng, 0.5, 2.),
                     angle = uniform(rng, 0., 6.28);
        p.set->add_cone(i, m);
        const double q  = active ? 1. : uniform(rng, 0.1, 0.8);
        p.x_star[i]     = s;
        p.x_star[i + 1] = q * m * s * std::cos(angle);
        p.x_star[i + 2] = q * m * s * std::sin(angle);
        if (active)
        {
          // h = ||x_t|| - m x_n, grad h = (-m, cos, sin)
          const double norm = std::sqrt(1. + m * m);
          p.g_star[i]       = -mu * (-m) / norm;
          p.g_star[i + 1]   = -mu * std::cos(angle) / norm;
          p.g_star[i + 2]   = -mu * std::sin(angle) / norm;
        }
      }
      if (active)
        ++p.n_active;
      i += size;
      ++block;
    }
    // free unknowns: anything, zero gradient
    for (; i < n; ++i)
      p.x_star[i] = uniform(rng, -1., 1.);
    p.set->finalize(p.x_star);
    return p;
  }

} // namespace

int
main()
{
  const unsigned int           n = 80;
  dealii::SparsityPattern      sp;
  dealii::SparseMatrix<double> A;
  qptest::random_sparse_spd(n, 2, 1., rng, sp, A);

  for (const std::string type :
       {"bound", "box", "disc", "ellipse", "cone", "mixed"})
  {
    const Planted p = plant(type, n);
    Problem<Vec>  problem;
    problem.hessian = [&](Vec &dst, const Vec &src) { A.vmult(dst, src); };
    problem.b.reinit(n);
    A.vmult(problem.b, p.x_star);
    problem.b -= p.g_star;
    problem.constraints = p.set;

    for (const std::string name : {"spg-qp", "pbbf", "apgd"})
    {
      SolverParameters prm;
      prm.solver         = name;
      prm.tolerance      = 1e-10;
      prm.max_iterations = 50000;
      auto       solver  = create<Vec>(prm);
      Vec        x(n);
      const auto stats = solver->solve(problem, x);
      Vec        error(x);
      error -= p.x_star;
      const double err = error.l2_norm();
      std::cout << "     " << name << " / " << type << " (" << p.n_active
                << " active blocks): " << stats.iterations << " iterations, "
                << stats.n_hessian_products << " products, "
                << stats.n_fall_back << " fall-backs, criterion "
                << stats.final_criterion << ", ||x - x*|| " << err << std::endl;
      check(stats.converged() &&
              err <= 1e-8 * std::max(1., p.x_star.l2_norm()) &&
              stats.kkt.feasibility <= 1e-12 &&
              stats.kkt.stationarity <= 1e-9 * stats.norm_b,
            name + " / " + type + ": converged to x*");
      check(qptest::history_consistent(stats) &&
              stats.history_iterations.back() == stats.iterations,
            name + " / " + type + ": history with time stamps and counts");

      prm.max_iterations = 5;
      auto       limited = create<Vec>(prm);
      Vec        y(n);
      const auto s = limited->solve(problem, y);
      check(s.reason == ConvergenceReason::max_iterations && !s.converged() &&
              s.iterations == 5,
            name + " / " + type +
              ": iteration limit 5 reported as max_iterations");
    }
  }
  return qptest::checker().finish("qp/spectral_planted");
}
