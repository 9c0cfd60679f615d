// Properties of SeparableSet projections and steps, per block type, on
// random samples: P(y) is feasible; P is idempotent and non-expansive;
// the obtuse-angle property <y - P(y), z - P(y)> <= 0 for feasible z, block
// by block; max_feasible_step(x, p) is exact (x - alpha p feasible, a
// slightly longer step is not) and feasible_step() leaves the blocking
// block active; the gradient splits agree with the one-sweep norms.
#include "planted_problems.h"

#include <qp/separable_set.h>

#include <algorithm>

using namespace qptest;
using Vec = dealii::Vector<double>;

namespace
{
  double
  dot(const Vec &a, const Vec &b, unsigned first, unsigned w)
  {
    double s = 0.;
    for (unsigned c = 0; c < w; ++c)
      s += a[first + c] * b[first + c];
    return s;
  }

  void
  test_type(const BlockType type, Checker &check)
  {
    const std::string name = dualcontact::qp::block_type_names.name(type);
    std::mt19937      rng(12345 + static_cast<int>(type));
    std::normal_distribution<double> normal(0., 1.5);
    const unsigned int               w        = width(type);
    const unsigned int               n_blocks = 40;
    const unsigned int               n        = n_blocks * w + 3; // + free

    double worst_feas = 0., worst_idem = 0., worst_expand = 0.,
           worst_obtuse = 0., worst_step_feas = 0.;
    unsigned int step_not_tight = 0, step_not_active = 0, n_finite = 0;
    double       worst_split = 0.;

    for (unsigned int trial = 0; trial < 50; ++trial)
    {
      std::vector<Block> blocks;
      for (unsigned k = 0; k < n_blocks; ++k)
        blocks.push_back(random_block(type, k * w, rng, 1e3));
      Vec  layout(n);
      auto set = make_set(blocks, layout);

      Vec y(n), z(n), py(n), pz(n);
      for (unsigned i = 0; i < n; ++i)
      {
        y[i] = normal(rng);
        z[i] = normal(rng);
      }
      set->project(y, py);
      set->project(z, pz);
      const double scale = 1. + y.linfty_norm();
      worst_feas = std::max(worst_feas, set->feasibility_violation(py) / scale);
      Vec ppy(py);
      set->project(ppy);
      ppy -= py;
      worst_idem = std::max(worst_idem, ppy.l2_norm() / scale);
      Vec dy(py), d(y);
      dy -= pz;
      d -= z;
      worst_expand =
        std::max(worst_expand, (dy.l2_norm() - d.l2_norm()) / scale);
      // obtuse angle, block by block, with the feasible point pz
      Vec r(y), s(pz);
      r -= py;
      s -= py;
      for (const Block &b : blocks)
      {
        const double ip = dot(r, s, b.first, w);
        const double nr = std::sqrt(dot(r, r, b.first, w));
        const double ns = std::sqrt(dot(s, s, b.first, w));
        worst_obtuse = std::max(worst_obtuse, ip / std::max(nr * ns, 1e-300));
      }

      // steps from a feasible point along a random direction, on sets of
      // two blocks so every block's formula gets to be the blocking one
      for (unsigned int k = 0; k + 1 < n_blocks; k += 2)
      {
        std::vector<Block> two = {blocks[k], blocks[k + 1]};
        two[1].first           = w;
        two[0].first           = 0;
        Vec  l2(2 * w);
        auto set2 = make_set(two, l2);
        Vec  x(2 * w), p(2 * w);
        for (unsigned i = 0; i < 2 * w; ++i)
        {
          x[i] = py[k * w + i];
          p[i] = normal(rng);
        }
        // half the time start strictly inside
        if (trial % 2)
          for (unsigned i = 0; i < 2 * w; ++i)
            x[i] = 0.5 * x[i] + 0.5 * pz[k * w + i];
        set2->project(x);
        const double alpha = set2->max_feasible_step(x, p);
        const double sc    = 1. + x.linfty_norm();
        if (std::isfinite(alpha))
        {
          ++n_finite;
          Vec xa(x), xl(x), xh(x);
          xa.add(-alpha, p);
          xl.add(-alpha * (1. + 1e-6) - 1e-9, p);
          xh.add(-0.5 * alpha, p);
          worst_step_feas = std::max(worst_step_feas,
                                     std::max(set2->feasibility_violation(xa),
                                              set2->feasibility_violation(xh)) /
                                       sc);
          if (!(set2->feasibility_violation(xl) > 0.))
            ++step_not_tight;
          Vec xs(x);
          set2->feasible_step(xs, p, alpha);
          const auto act   = set2->n_active_blocks(xs);
          unsigned   n_act = 0;
          for (auto a : act)
            n_act += a;
          if (n_act == 0 && alpha > 0.)
            ++step_not_active;
        }
        else
        {
          Vec xf(x);
          xf.add(-1e6, p);
          worst_step_feas =
            std::max(worst_step_feas,
                     set2->feasibility_violation(xf) / sc / 1e6);
        }
      }

      // gradient splits: phi + beta = g^P, norms agree with vectors
      Vec g(n), phi(n), beta(n), gp(n), rg(n), rpg(n), mask(n), za(n);
      for (unsigned i = 0; i < n; ++i)
        g[i] = normal(rng);
      set->split_gradient(py, g, phi, beta);
      set->projected_gradient(py, g, gp);
      const auto   nrm  = set->gradient_norms(py, g);
      const double alph = 0.3;
      const auto   rnrm = set->reduced_gradient_norms(py, g, alph);
      set->reduced_gradient(py, g, alph, rg);
      set->reduced_projected_gradient(py, g, alph, rpg);
      Vec sum(phi);
      sum += beta;
      sum -= gp;
      double e = sum.l2_norm();
      e        = std::max(e, std::abs(phi.norm_sqr() - nrm.free_sq));
      e        = std::max(e, std::abs(beta.norm_sqr() - nrm.chopped_sq));
      e        = std::max(e,
                   std::abs(rpg.norm_sqr() -
                            (rnrm.free_sq + rnrm.reduced_chopped_sq)));
      e        = std::max(e,
                   std::abs(rg.l2_norm() -
                            set->reduced_gradient_norm(py, g, alph)));
      za       = g;
      set->zero_active(py, za);
      za -= phi;
      e = std::max(e, za.l2_norm());
      set->active_mask(py, mask);
      for (unsigned i = 0; i < n; ++i)
        if (mask[i] == 1.)
          e = std::max(e, std::abs(phi[i]));
        else
          e = std::max(e, std::abs(phi[i] - g[i]) + std::abs(beta[i]));
      worst_split = std::max(worst_split, e / (1. + g.norm_sqr()));
    }
    check.check(worst_feas <= 1e-15,
                name + ": P(y) feasible (worst " + sci(worst_feas) + ")");
    check.check(worst_idem <= 1e-15,
                name + ": P(P(y)) = P(y) (worst rel. " + sci(worst_idem) + ")");
    check.check(worst_expand <= 1e-14,
                name + ": ||P(y)-P(z)|| <= ||y-z|| (worst excess " +
                  sci(worst_expand) + ")");
    check.check(worst_obtuse <= 1e-12,
                name + ": <y-P(y), z-P(y)> <= 0 per block (worst cosine " +
                  sci(worst_obtuse) + ")");
    check.check(worst_step_feas <= 1e-14,
                name + ": x - alpha p and x - alpha/2 p feasible (worst " +
                  sci(worst_step_feas) + ")");
    check.check(step_not_tight == 0 && n_finite > 0,
                name + ": x - (1+1e-6) alpha p infeasible (" +
                  std::to_string(step_not_tight) + " of " +
                  std::to_string(n_finite) + " steps not tight)");
    check.check(step_not_active == 0,
                name + ": feasible_step leaves a block active (" +
                  std::to_string(step_not_active) + " failures)");
    check.check(worst_split <= 1e-13,
                name + ": phi+beta=g^P, norms, masks consistent (worst " +
                  sci(worst_split) + ")");
  }
} // namespace

int
main()
{
  Checker check;
  for (const BlockType t : {BlockType::bound,
                            BlockType::box,
                            BlockType::disc,
                            BlockType::ellipse,
                            BlockType::cone})
    test_type(t, check);
  return check.finish("set_projection");
}
