// The fused passes of SeparableSet (cg_step, conjugate_direction,
// projected_step), which the active-set solvers use instead of separate
// calls to save memory traffic, against those separate calls, on random
// sets of every block type mixed with free unknowns, at feasible points
// with many active blocks (a projected random vector):
//  - cg_step: x - alpha p, g - alpha Ap, gradient_norms() at the new point
//    and phi'Ap; with a reduced alpha also reduced_gradient_norms();
//  - conjugate_direction: phi - beta p (p on the free set), the
//    max_feasible_step() along it (finite and positive), p'p, g'p (also
//    beta = 0, the restart);
//  - projected_step: P(x - alpha g) and P(x - alpha phi).
// Every value to 1e-13 relative (they differ only in summation order).
#include "planted_problems.h"

#include <qp/separable_set.h>

#include <cmath>
#include <random>

using namespace qptest;
using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

namespace
{
  double
  rel(const double a, const double b)
  {
    if (a == b) // also both infinite
      return 0.;
    return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300});
  }

  double
  rel(const Vec &a, const Vec &b)
  {
    Vec d(a);
    d -= b;
    return d.l2_norm() / std::max(b.l2_norm(), 1e-300);
  }
} // namespace

int
main()
{
  Checker check;
  struct Case
  {
    std::string            name;
    std::vector<BlockType> types;
  };
  const std::vector<Case> cases = {{"bound", {BlockType::bound}},
                                   {"box", {BlockType::box}},
                                   {"bound+box",
                                    {BlockType::bound, BlockType::box}},
                                   {"mixed",
                                    {BlockType::bound,
                                     BlockType::box,
                                     BlockType::disc,
                                     BlockType::ellipse,
                                     BlockType::cone}}};
  for (const Case &c : cases)
    for (const unsigned int seed : {1u, 2u, 3u})
    {
      std::mt19937       rng(seed);
      std::vector<Block> blocks;
      unsigned int       n = 0;
      for (unsigned int k = 0; k < 200; ++k)
      {
        const BlockType t = c.types[k % c.types.size()];
        blocks.push_back(random_block(t, n, rng));
        n += width(t);
        if (k % 7 == 0)
          n += 2; // free unknowns between blocks
      }
      Vec        layout(n);
      const auto set = make_set(blocks, layout);

      std::normal_distribution<double> normal;
      Vec                              x(n), g(n), p(n), Ap(n);
      for (unsigned int i = 0; i < n; ++i)
      {
        x[i]  = 2. * normal(rng);
        g[i]  = normal(rng);
        p[i]  = normal(rng);
        Ap[i] = normal(rng);
      }
      set->project(x); // feasible, with many active blocks
      const double      alpha = 1e-3, beta = 0.7;
      const std::string tag = c.name + "/" + std::to_string(seed) + ": ";
      check.verbose         = false;
      {
        const auto active = set->n_active_blocks(x);
        unsigned   total  = 0;
        for (const auto a : active)
          total += a;
        check.check(total > 20 && total < 180,
                    tag + "many but not all blocks active (" +
                      std::to_string(total) + ")");
      }

      // cg_step
      {
        Vec xr(x), gr(g), phi(n);
        xr.add(-alpha, p);
        gr.add(-alpha, Ap);
        const GradientNorms nr = set->gradient_norms(xr, gr);
        set->free_gradient(xr, gr, phi);
        const double phiAp_r = phi * Ap;

        Vec                 xf(x), gf(g);
        double              phiAp = 0.;
        const GradientNorms nf    = set->cg_step(xf, gf, p, Ap, alpha, phiAp);
        check.check(rel(xf, xr) <= 1e-15 && rel(gf, gr) <= 1e-15,
                    tag + "cg_step: x and g");
        check.check(rel(nf.free_sq, nr.free_sq) <= 1e-13 &&
                      rel(nf.chopped_sq, nr.chopped_sq) <= 1e-13 &&
                      rel(phiAp, phiAp_r) <= 1e-13,
                    tag + "cg_step: ||phi||^2 " + sci(nf.free_sq) + " vs " +
                      sci(nr.free_sq) + ", ||beta||^2 " + sci(nf.chopped_sq) +
                      " vs " + sci(nr.chopped_sq) + ", phi'Ap " + sci(phiAp) +
                      " vs " + sci(phiAp_r));

        // with the reduced chopped gradient (MwPGP's CG step)
        const double        ra = 0.7 / (1. + alpha);
        const GradientNorms rr = set->reduced_gradient_norms(xr, gr, ra);
        Vec                 xw(x), gw(g);
        double              phiAp_w = 0.;
        const GradientNorms nw =
          set->cg_step(xw, gw, p, Ap, alpha, phiAp_w, ra);
        check.check(rel(xw, xr) <= 1e-15 && rel(gw, gr) <= 1e-15 &&
                      rel(nw.free_sq, rr.free_sq) <= 1e-13 &&
                      rel(nw.chopped_sq, rr.chopped_sq) <= 1e-13 &&
                      rel(nw.reduced_chopped_sq, rr.reduced_chopped_sq) <=
                        1e-13 &&
                      rel(phiAp_w, phiAp_r) <= 1e-13,
                    tag + "cg_step (reduced): ||beta~||^2 " +
                      sci(nw.reduced_chopped_sq) + " vs " +
                      sci(rr.reduced_chopped_sq));
        check.check(nf.reduced_chopped_sq == 0.,
                    tag + "cg_step: no reduced norm without its alpha");
      }

      // conjugate_direction (and the restart beta = 0), with the old
      // direction on the free set as in CG (else a block on its
      // boundary with an outward direction makes every step 0)
      set->zero_active(x, p);
      for (const double b : {beta, 0.})
      {
        Vec phi(n), pr(p);
        set->free_gradient(x, g, phi);
        pr.sadd(-b, 1., phi);
        const double step_r = set->max_feasible_step(x, pr);
        Vec          pf(p);
        const auto   d = set->conjugate_direction(x, g, b, pf);
        check.check(rel(pf, pr) <= 1e-15,
                    tag + "conjugate_direction: p, beta = " + sci(b));
        check.check(rel(d.max_step, step_r) <= 1e-13 &&
                      rel(d.pp, pr * pr) <= 1e-13 && rel(d.gp, g * pr) <= 1e-13,
                    tag + "conjugate_direction: step " + sci(d.max_step) +
                      " vs " + sci(step_r) + ", p'p, g'p, beta = " + sci(b));
        check.check(step_r > 0. && std::isfinite(step_r),
                    tag + "a finite positive feasible step is tested (" +
                      sci(step_r) + ")");
      }

      // projected_step along g and along phi
      for (const bool free_only : {false, true})
      {
        Vec d(g), xr(x);
        if (free_only)
          set->free_gradient(x, g, d);
        xr.add(-0.5, d);
        set->project(xr);
        Vec xf(x);
        set->projected_step(xf, g, 0.5, free_only);
        check.check(rel(xf, xr) <= 1e-15,
                    tag + "projected_step along " + (free_only ? "phi" : "g") +
                      ": " + sci(rel(xf, xr)));
      }
    }
  return check.finish("fused_passes");
}
