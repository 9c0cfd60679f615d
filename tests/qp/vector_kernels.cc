// qp::VectorKernels, whichever clone the loader picked on this machine
// (printed), against scalar loops that follow the documented lane order
// (lane j takes the entries i = j mod 8 of a run; of a remainder of four to
// seven entries the first four go to lanes 0-3; the last one to three
// entries go to lane 0) and the expressions of a bound block
// (qp::blocks::Bound: active test, chopped and reduced chopped gradient,
// largest and feasible step, projection):
//  - every sum and every vector written bitwise equal, so that the results
//    do not depend on the machine's instruction set;
//  - the largest feasible steps (max_step, conjugate_direction) equal to
//    the least room/p over p > 0 found by Bound::offer_step entry by entry;
//  - p'Ap within 1e-14 (sum of |terms|) of the sum in long double;
// on runs of 0 to 1001 entries with active, nearly active, infeasible and
// free entries, lower bounds of both signs and zero (also -0), directions
// with zeros of both signs, and lanes that already hold partial sums.
#include "planted_problems.h"

#include <qp/blocks/bound.h>
#include <qp/vector_kernels.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace qptest;
using dualcontact::qp::VectorKernels;
using dualcontact::qp::blocks::Bound;
using Lanes      = VectorKernels::Lanes;
using RatioLanes = VectorKernels::RatioLanes;

namespace
{
  constexpr double tol = 1e-12;

  // the lane of entry i of a run of n
  unsigned int
  lane(const std::size_t i, const std::size_t n)
  {
    const std::size_t m8 = n - n % 8;
    if (i < m8)
      return i % 8;
    if (n - m8 >= 4 && i < m8 + 4)
      return i - m8;
    return 0;
  }

  bool
  same_bits(const double a, const double b)
  {
    return std::memcmp(&a, &b, sizeof(double)) == 0;
  }

  bool
  same_bits(const std::vector<double> &a, const std::vector<double> &b)
  {
    if (a.size() != b.size())
      return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!same_bits(a[i], b[i]))
        return false;
    return true;
  }

  bool
  same_bits(const Lanes &a, const Lanes &b)
  {
    for (unsigned int j = 0; j < VectorKernels::lanes; ++j)
      if (!same_bits(a.v[j], b.v[j]))
        return false;
    return true;
  }

  // lanes that already hold something (a previous run)
  Lanes
  start_lanes(std::mt19937 &rng)
  {
    Lanes s;
    for (double &v : s.v)
      v = uniform(rng, 0., 1.);
    return s;
  }

  bool
  is_active(const double x, const double l)
  {
    return Bound{l}.classify(&x, tol).active;
  }

  // the largest feasible step of bound blocks (Bound::offer_step), entry
  // by entry
  struct Ratio
  {
    double num = 1., den = 0.;
    void
    offer(const double x, const double l, const double p)
    {
      dualcontact::qp::blocks::MinRatio ratio{num, den};
      Bound{l}.offer_step(&x, &p, ratio);
    }
    double
    value() const
    {
      return den > 0. ? num / den : std::numeric_limits<double>::infinity();
    }
  };

  bool
  close(const double a, const double b, const double rel)
  {
    if (a == b)
      return true;
    return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b));
  }

  struct Data
  {
    std::vector<double> x, g, p, Ap, l, b;
  };

  Data
  make_data(std::mt19937 &rng, const std::size_t n)
  {
    Data d;
    for (std::size_t i = 0; i < n; ++i)
    {
      const unsigned int kind = rng() % 10;
      double             l    = uniform(rng, -2., 2.);
      if (kind == 0)
        l = 0.;
      else if (kind == 1)
        l = -0.;
      double             room  = uniform(rng, 0., 1.);
      const unsigned int state = rng() % 10;
      if (state < 3)
        room = 0.; // active
      else if (state == 3)
        room = 0.5 * tol * std::abs(l); // active by the tolerance
      else if (state == 4)
        room = -uniform(rng, 0., 1e-3); // infeasible
      d.l.push_back(l);
      d.x.push_back(l + room);
      d.g.push_back(uniform(rng, -1., 1.));
      double             p   = uniform(rng, -1., 1.);
      const unsigned int dir = rng() % 10;
      if (dir == 0)
        p = 0.;
      else if (dir == 1)
        p = -0.;
      d.p.push_back(p);
      d.Ap.push_back(uniform(rng, -3., 3.));
      d.b.push_back(uniform(rng, -1., 1.));
    }
    return d;
  }
} // namespace

int
main()
{
  Checker &c = checker();
  c.verbose  = false;
  std::cout << "vector kernels: " << VectorKernels::instruction_set()
            << std::endl;
  std::mt19937                   rng(20261121);
  const std::vector<std::size_t> sizes = {0,  1,  2,  3,   4,   5,  6,  7,
                                          8,  9,  11, 12,  13,  15, 16, 17,
                                          19, 20, 23, 24,  25,  28, 31, 32,
                                          33, 47, 64, 100, 1001};
  for (const std::size_t n : sizes)
  {
    const std::string at = " (n = " + std::to_string(n) + ")";
    const Data        d  = make_data(rng, n);

    // dots, dot
    {
      Lanes a = start_lanes(rng), b = start_lanes(rng), e = start_lanes(rng);
      Lanes ra = a, rb = b, re = e;
      long double exact = 0., magnitude = 0.;
      for (double v : a.v)
      {
        exact += v;
        magnitude += std::abs(v);
      }
      for (std::size_t i = 0; i < n; ++i)
      {
        const unsigned int j = lane(i, n);
        ra.v[j] += d.p[i] * d.Ap[i];
        rb.v[j] += d.p[i] * d.p[i];
        re.v[j] += d.g[i] * d.p[i];
        exact += (long double)d.p[i] * d.Ap[i];
        magnitude += std::abs((long double)d.p[i] * d.Ap[i]);
      }
      VectorKernels::dots(n, d.p.data(), d.Ap.data(), d.g.data(), a, b, e);
      c.check(same_bits(a, ra) && same_bits(b, rb) && same_bits(e, re),
              "dots: lanes bitwise" + at);
      c.check(std::abs(a.total() - double(exact)) <= 1e-14 * magnitude,
              "dots: p'Ap within 1e-14 sum |terms| of long double" + at);
      Lanes s = start_lanes(rng), rs = s;
      for (std::size_t i = 0; i < n; ++i)
        rs.v[lane(i, n)] += d.g[i] * d.Ap[i];
      VectorKernels::dot(n, d.g.data(), d.Ap.data(), s);
      c.check(same_bits(s, rs), "dot: lanes bitwise" + at);
    }

    // cg_step
    {
      const double        alpha = uniform(rng, 0., 0.5);
      std::vector<double> x = d.x, g = d.g, rx = d.x, rg = d.g;
      Lanes fs = start_lanes(rng), bs = start_lanes(rng), pa = start_lanes(rng);
      Lanes rfs = fs, rbs = bs, rpa = pa;
      for (std::size_t i = 0; i < n; ++i)
      {
        rx[i] -= alpha * d.p[i];
        rg[i] -= alpha * d.Ap[i];
        const bool         active = is_active(rx[i], d.l[i]);
        const double       gm     = std::min(rg[i], 0.);
        const unsigned int j      = lane(i, n);
        rfs.v[j] += active ? 0. : rg[i] * rg[i];
        rbs.v[j] += active ? gm * gm : 0.;
        rpa.v[j] += active ? 0. : rg[i] * d.Ap[i];
      }
      VectorKernels::cg_step(n,
                             x.data(),
                             g.data(),
                             d.p.data(),
                             d.Ap.data(),
                             d.l.data(),
                             tol,
                             alpha,
                             fs,
                             bs,
                             pa);
      c.check(same_bits(x, rx) && same_bits(g, rg),
              "cg_step: x, g bitwise" + at);
      c.check(same_bits(fs, rfs) && same_bits(bs, rbs) && same_bits(pa, rpa),
              "cg_step: lanes bitwise" + at);
    }

    // cg_step_reduced: cg_step and the reduced chopped gradient (the
    // sweep's expression for an active bound) at the new point
    {
      const double alpha = uniform(rng, 0., 0.5), ra = uniform(rng, 0.1, 2.);
      std::vector<double> x = d.x, g = d.g, rx = d.x, rg = d.g;
      Lanes fs = start_lanes(rng), bs = start_lanes(rng), pa = start_lanes(rng),
            rs  = start_lanes(rng);
      Lanes rfs = fs, rbs = bs, rpa = pa, rrs = rs;
      for (std::size_t i = 0; i < n; ++i)
      {
        rx[i] -= alpha * d.p[i];
        rg[i] -= alpha * d.Ap[i];
        const bool         active = is_active(rx[i], d.l[i]);
        const double       y = rx[i], gi = rg[i];
        const double       gm  = std::min(gi, 0.);
        const unsigned int j   = lane(i, n);
        double             red = 0.;
        if (active)
          Bound{d.l[i]}.reduced_chopped_gradient(&y, &gi, ra, {true}, &red);
        rfs.v[j] += active ? 0. : gi * gi;
        rbs.v[j] += active ? gm * gm : 0.;
        rpa.v[j] += active ? 0. : gi * d.Ap[i];
        rrs.v[j] += red * red;
      }
      VectorKernels::cg_step_reduced(n,
                                     x.data(),
                                     g.data(),
                                     d.p.data(),
                                     d.Ap.data(),
                                     d.l.data(),
                                     tol,
                                     alpha,
                                     ra,
                                     fs,
                                     bs,
                                     pa,
                                     rs);
      c.check(same_bits(x, rx) && same_bits(g, rg) && same_bits(fs, rfs) &&
                same_bits(bs, rbs) && same_bits(pa, rpa) && same_bits(rs, rrs),
              "cg_step_reduced: x, g, lanes bitwise" + at);
    }

    // conjugate_direction
    for (const double beta : {0., 0.37})
    {
      std::vector<double> p = d.p, rp = d.p;
      Lanes               pp = start_lanes(rng), gp = start_lanes(rng);
      Lanes               rpp = pp, rgp = gp;
      RatioLanes          ratio;
      Ratio               reference;
      for (std::size_t i = 0; i < n; ++i)
      {
        const bool         active = is_active(d.x[i], d.l[i]);
        const double       di     = (active ? 0. : d.g[i]) - beta * rp[i];
        const unsigned int j      = lane(i, n);
        rp[i]                     = di;
        rpp.v[j] += di * di;
        rgp.v[j] += d.g[i] * di;
        reference.offer(d.x[i], d.l[i], di);
      }
      VectorKernels::conjugate_direction(n,
                                         d.x.data(),
                                         d.g.data(),
                                         d.l.data(),
                                         tol,
                                         beta,
                                         p.data(),
                                         pp,
                                         gp,
                                         ratio);
      c.check(same_bits(p, rp), "conjugate_direction: p bitwise" + at);
      c.check(same_bits(pp, rpp) && same_bits(gp, rgp),
              "conjugate_direction: lanes bitwise" + at);
      c.check(close(VectorKernels::min_ratio(ratio), reference.value(), 1e-15),
              "conjugate_direction: largest feasible step " +
                sci(VectorKernels::min_ratio(ratio)) + at);
    }

    // reduced_norms (SeparableSet's sweep for a bound block)
    {
      const double alpha = uniform(rng, 0.1, 2.);
      Lanes fs = start_lanes(rng), bs = start_lanes(rng), rs = start_lanes(rng);
      Lanes rfs = fs, rbs = bs, rrs = rs;
      for (std::size_t i = 0; i < n; ++i)
      {
        const bool         active = is_active(d.x[i], d.l[i]);
        const double       y = d.x[i], gi = d.g[i];
        const unsigned int j   = lane(i, n);
        const double       phi = active ? 0. : gi,
                     beta      = active ? std::min(gi, 0.) : 0.;
        double red             = 0.;
        if (active)
          Bound{d.l[i]}.reduced_chopped_gradient(&y, &gi, alpha, {true}, &red);
        rfs.v[j] += phi * phi;
        rbs.v[j] += beta * beta;
        rrs.v[j] += red * red;
      }
      VectorKernels::reduced_norms(
        n, d.x.data(), d.g.data(), d.l.data(), tol, alpha, fs, bs, rs);
      c.check(same_bits(fs, rfs) && same_bits(bs, rbs) && same_bits(rs, rrs),
              "reduced_norms: lanes bitwise" + at);
    }

    // max_step
    {
      RatioLanes ratio;
      Ratio      reference;
      for (std::size_t i = 0; i < n; ++i)
        reference.offer(d.x[i], d.l[i], d.p[i]);
      VectorKernels::max_step(n, d.x.data(), d.p.data(), d.l.data(), ratio);
      c.check(close(VectorKernels::min_ratio(ratio), reference.value(), 1e-15),
              "max_step: " + sci(VectorKernels::min_ratio(ratio)) + " vs " +
                sci(reference.value()) + at);
    }

    // gradient_norms, with and without phi
    for (const bool with_phi : {true, false})
    {
      std::vector<double> phi(n, 7.), rphi(n, 7.);
      Lanes               fs = start_lanes(rng), bs = start_lanes(rng);
      Lanes               rfs = fs, rbs = bs;
      for (std::size_t i = 0; i < n; ++i)
      {
        const bool         active = is_active(d.x[i], d.l[i]);
        const double       gm     = std::min(d.g[i], 0.);
        const unsigned int j      = lane(i, n);
        if (with_phi)
          rphi[i] = active ? 0. : d.g[i];
        rfs.v[j] += active ? 0. : d.g[i] * d.g[i];
        rbs.v[j] += active ? gm * gm : 0.;
      }
      VectorKernels::gradient_norms(n,
                                    d.x.data(),
                                    d.g.data(),
                                    d.l.data(),
                                    tol,
                                    with_phi ? phi.data() : nullptr,
                                    fs,
                                    bs);
      c.check(same_bits(phi, rphi) && same_bits(fs, rfs) && same_bits(bs, rbs),
              std::string("gradient_norms") + (with_phi ? "" : " (no phi)") +
                ": bitwise" + at);
    }

    // feasible_step
    {
      const double        alpha = uniform(rng, 0., 2.);
      std::vector<double> x = d.x, rx = d.x;
      for (std::size_t i = 0; i < n; ++i)
        Bound{d.l[i]}.feasible_step(&rx[i], &d.p[i], alpha);
      VectorKernels::feasible_step(n, x.data(), d.p.data(), d.l.data(), alpha);
      c.check(same_bits(x, rx), "feasible_step: bitwise" + at);
    }

    // projected_step, along g and along the free gradient
    for (const bool free_only : {false, true})
    {
      const double        alpha = uniform(rng, -0.5, 2.);
      std::vector<double> x = d.x, rx = d.x;
      for (std::size_t i = 0; i < n; ++i)
      {
        const bool active = free_only && is_active(rx[i], d.l[i]);
        rx[i] -= alpha * (active ? 0. : d.g[i]);
        Bound{d.l[i]}.project(&rx[i]);
      }
      VectorKernels::projected_step(
        n, x.data(), d.g.data(), d.l.data(), tol, alpha, free_only);
      c.check(same_bits(x, rx),
              std::string("projected_step") + (free_only ? " (free)" : "") +
                ": bitwise" + at);
    }

    // step, step_differences (with and without the copy), extrapolate:
    // elementwise in the expressions of the loops they replaced
    {
      const double        beta = uniform(rng, -1., 1.);
      std::vector<double> x = d.x, g = d.g, rx = d.x, rg = d.g;
      for (std::size_t i = 0; i < n; ++i)
      {
        rx[i] += beta * d.p[i];
        rg[i] += beta * d.Ap[i];
      }
      VectorKernels::step(n, beta, d.p.data(), d.Ap.data(), x.data(), g.data());
      c.check(same_bits(x, rx) && same_bits(g, rg), "step: bitwise" + at);

      for (const bool copy : {false, true})
      {
        std::vector<double> xp = d.p, gp = d.Ap;
        Lanes ss = start_lanes(rng), sy = start_lanes(rng), rss = ss, rsy = sy;
        for (std::size_t i = 0; i < n; ++i)
        {
          const double si = d.x[i] - d.p[i], yi = d.g[i] - d.Ap[i];
          rss.v[lane(i, n)] += si * si;
          rsy.v[lane(i, n)] += si * yi;
        }
        VectorKernels::step_differences(
          n, d.x.data(), d.g.data(), xp.data(), gp.data(), copy, ss, sy);
        c.check(same_bits(ss, rss) && same_bits(sy, rsy) &&
                  same_bits(xp, copy ? d.x : d.p) &&
                  same_bits(gp, copy ? d.g : d.Ap),
                std::string("step_differences") + (copy ? " (copy)" : "") +
                  ": bitwise" + at);
      }

      std::vector<double> eg(n), ey(n), egy(n), rgo(n), ry(n), rgy(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        // the deal.II operations APGD made: g = Ax; g -= b; y = x;
        // y.sadd(1 + beta, -beta, x_old); gy = Ax; gy.sadd(...); gy -= b
        rgo[i] = d.Ap[i] - d.b[i];
        ry[i]  = (1. + beta) * d.x[i] + -beta * d.p[i];
        rgy[i] = ((1. + beta) * d.Ap[i] + -beta * d.g[i]) - d.b[i];
      }
      VectorKernels::extrapolate(n,
                                 beta,
                                 d.x.data(),
                                 d.p.data(),
                                 d.Ap.data(),
                                 d.g.data(),
                                 d.b.data(),
                                 eg.data(),
                                 ey.data(),
                                 egy.data());
      c.check(same_bits(eg, rgo) && same_bits(ey, ry) && same_bits(egy, rgy),
              "extrapolate: bitwise" + at);
    }

    // cost, residual_cost
    {
      Lanes s = start_lanes(rng), rs = s;
      for (std::size_t i = 0; i < n; ++i)
        rs.v[lane(i, n)] += d.x[i] * (d.g[i] - d.b[i]);
      VectorKernels::cost(n, d.x.data(), d.g.data(), d.b.data(), s);
      c.check(same_bits(s, rs), "cost: lanes bitwise" + at);
      std::vector<double> g = d.Ap, rg = d.Ap;
      Lanes               t = start_lanes(rng), rt = t;
      for (std::size_t i = 0; i < n; ++i)
      {
        rg[i] -= d.b[i];
        rt.v[lane(i, n)] += d.x[i] * (rg[i] - d.b[i]);
      }
      VectorKernels::residual_cost(n, d.x.data(), d.b.data(), g.data(), t);
      c.check(same_bits(g, rg) && same_bits(t, rt),
              "residual_cost: g and lanes bitwise" + at);
    }
  }

  // Lanes::total adds lane 0 + 1 + ... + 7 in this order
  {
    Lanes s;
    for (unsigned int j = 0; j < VectorKernels::lanes; ++j)
      s.v[j] = j == 0 ? 1. : 1e-16;
    c.check(s.total() == 1., "total: lanes added from lane 0 on (rounding)");
  }
  // an empty ratio means no bound limits the step
  c.check(std::isinf(VectorKernels::min_ratio(RatioLanes())),
          "min_ratio: infinite with nothing offered");
  return c.finish("vector_kernels");
}
