// Tiny QPs with closed-form solutions, one or two per set type, solved by
// every core solver that accepts the set:
//  - A = I: the solution is P(b) (minimizing 1/2||x - b||^2);
//  - bound 2x2: A = [2 -1; -1 2], b = (-1, 1), x >= 0  ->  (0, 1/2);
//  - disc: A = diag(1, 4), b = (2, 0), ||x|| <= 1  ->  (1, 0);
//  - box with l = u, cone apex, rotated ellipse.
// Also: at the solution g^P, g~_alpha and g~^P_alpha vanish, the active
// blocks are those on the boundary (is_active, n_active_blocks) and the
// complementarity measure is 0; at a non-solution the gradients do not
// vanish.
#include "planted_problems.h"

#include <qp/solver_factory.h>

using namespace qptest;
using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

namespace
{
  struct Tiny
  {
    std::string         name;
    Dense               A;
    std::vector<double> b;
    std::vector<Block>  blocks;
    std::vector<double> x_star;
  };

  Dense
  diag(const std::vector<double> &d)
  {
    Dense A;
    A.n = d.size();
    A.a.assign(A.n * A.n, 0.);
    for (unsigned i = 0; i < A.n; ++i)
      A.a[i * A.n + i] = d[i];
    return A;
  }
} // namespace

int
main()
{
  Checker           check;
  std::vector<Tiny> cases;
  const double      pi = 3.141592653589793;
  // identity Hessian: x* = P(b); one free unknown at the end (x* = b)
  cases.push_back({"bound I",
                   diag({1, 1, 1}),
                   {-2, 3, 7},
                   {{BlockType::bound, 0, 0.5}, {BlockType::bound, 1, 0.5}},
                   {0.5, 3, 7}});
  cases.push_back({"box I",
                   diag({1, 1, 1, 1}),
                   {5, -5, 0.3, -1},
                   {{BlockType::box, 0, -1, 2},
                    {BlockType::box, 1, -1, 2},
                    {BlockType::box, 2, 0.5, 0.5}},
                   {2, -1, 0.5, -1}});
  cases.push_back({"disc I",
                   diag({1, 1, 1}),
                   {3, 4, 2},
                   {{BlockType::disc, 0, 2.5}},
                   {1.5, 2, 2}});
  cases.push_back({"ellipse I",
                   diag({1, 1, 1}),
                   {3, 0, 1},
                   {{BlockType::ellipse, 0, 2, 1, 0.}},
                   {2, 0, 1}});
  cases.push_back({"ellipse rotated I",
                   diag({1, 1, 1}),
                   {0, 3, 1},
                   {{BlockType::ellipse, 0, 2, 1, pi / 2}},
                   {0, 2, 1}});
  cases.push_back({"cone I (boundary)",
                   diag({1, 1, 1, 1}),
                   {1, 2, 0, -3},
                   {{BlockType::cone, 0, 0.5}},
                   {1.6, 0.8, 0, -3}});
  cases.push_back({"cone I (apex)",
                   diag({1, 1, 1, 1}),
                   {-1, 2, 0, 4},
                   {{BlockType::cone, 0, 0.5}},
                   {0, 0, 0, 4}});
  {
    Dense A;
    A.n = 2;
    A.a = {2, -1, -1, 2};
    cases.push_back({"bound 2x2",
                     A,
                     {-1, 1},
                     {{BlockType::bound, 0, 0.}, {BlockType::bound, 1, 0.}},
                     {0, 0.5}});
  }
  cases.push_back({"disc diag(1,4)",
                   diag({1, 4}),
                   {2, 0},
                   {{BlockType::disc, 0, 1.}},
                   {1, 0}});

  for (const Tiny &t : cases)
  {
    bool bounds_only = true;
    for (const Block &b : t.blocks)
      bounds_only &= (b.type == BlockType::bound || b.type == BlockType::box);
    Vec  layout(t.b.size());
    auto problem = make_problem(t.A, t.b, t.blocks, layout);
    for (const std::string solver : {"mprgp", "mpgp", "mpgp-bb", "mwpgp"})
    {
      if (solver == "mprgp" && !bounds_only)
        continue;
      SolverParameters prm;
      prm.tolerance = 1e-12;
      Vec          x(t.b.size());
      const auto   stats = create<Vec>(solver, prm)->solve(problem, x);
      const double err   = distance(x, t.x_star);
      check.check(stats.converged() && err <= 1e-10,
                  t.name + " / " + solver + ": x = x* (error " + sci(err) +
                    ", " + to_string(stats.reason) + ", " +
                    std::to_string(stats.iterations) + " iterations)");
    }
    // gradients vanish at x*, not at a perturbed feasible point
    Vec xs(t.b.size()), g(t.b.size()), gp(t.b.size()), work(t.b.size());
    fill(xs, t.x_star);
    problem.hessian(g, xs);
    g -= problem.b;
    const auto  &set   = *problem.constraints;
    const double alpha = 0.5;
    set.projected_gradient(xs, g, gp);
    const double n_p = gp.l2_norm();
    const double n_r = set.reduced_gradient_norm(xs, g, alpha);
    set.reduced_projected_gradient(xs, g, alpha, gp);
    const double n_rp = gp.l2_norm();
    check.check(n_p <= 1e-14 && n_r <= 1e-14 && n_rp <= 1e-14,
                t.name + ": g^P, g~, g~^P vanish at x* (" + sci(n_p) + ", " +
                  sci(n_r) + ", " + sci(n_rp) + ")");
    // active-set queries and complementarity at x*
    {
      unsigned int n_boundary = 0, n_is_active = 0;
      for (const Block &blk : t.blocks)
      {
        const double *z           = &t.x_star[blk.first];
        bool          on_boundary = false;
        switch (blk.type)
        {
          case BlockType::bound:
            on_boundary = z[0] == blk.p1;
            break;
          case BlockType::box:
            on_boundary = z[0] == blk.p1 || z[0] == blk.p2;
            break;
          case BlockType::disc:
            on_boundary = std::abs(std::hypot(z[0], z[1]) - blk.p1) <= 1e-12;
            break;
          case BlockType::ellipse:
          {
            const double c = std::cos(blk.p3), sn = std::sin(blk.p3);
            const double y1 = c * z[0] + sn * z[1], y2 = -sn * z[0] + c * z[1];
            on_boundary =
              std::abs(std::hypot(y1 / blk.p1, y2 / blk.p2) - 1.) <= 1e-12;
            break;
          }
          case BlockType::cone:
            on_boundary =
              z[0] <= 0. || blk.p1 * z[0] - std::hypot(z[1], z[2]) <=
                              1e-12 * std::hypot(z[0], z[1], z[2]);
            break;
        }
        n_boundary += on_boundary ? 1 : 0;
        n_is_active += set.is_active(xs, blk.first) == on_boundary ? 1 : 0;
      }
      const auto   counts = set.n_active_blocks(xs);
      unsigned int total  = 0;
      for (const auto c : counts)
        total += c;
      Vec gs(xs);
      problem.hessian(gs, xs);
      gs -= problem.b;
      const double comp = set.complementarity(xs, gs);
      check.check(n_is_active == t.blocks.size() && total == n_boundary &&
                    comp <= 1e-14,
                  t.name + ": " + std::to_string(n_boundary) + " of " +
                    std::to_string(t.blocks.size()) +
                    " blocks on the boundary = is_active = n_active_blocks; "
                    "complementarity at x* " +
                    sci(comp));
    }
    Vec y(xs);
    y.add(0.3, problem.b);
    set.project(y);
    problem.hessian(g, y);
    g -= problem.b;
    set.projected_gradient(y, g, gp);
    const double m_p = gp.l2_norm();
    const double m_r = set.reduced_gradient_norm(y, g, alpha);
    set.reduced_projected_gradient(y, g, alpha, gp);
    const double m_rp = gp.l2_norm();
    work              = y;
    work.add(-1., xs);
    if (work.l2_norm() > 1e-8)
      check.check(m_p > 1e-6 && m_r > 1e-6 && m_rp > 1e-6,
                  t.name + ": they do not vanish at another point (" +
                    sci(m_p) + ", " + sci(m_r) + ", " + sci(m_rp) + ")");
  }
  return check.finish("closed_form");
}
