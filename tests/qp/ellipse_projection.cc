// Euclidean projection onto an ellipse (safeguarded Newton on the secular
// equation) against an independent brute-force search: dense sampling of
// the boundary (a cos t, b sin t), then bisection on the derivative of the
// squared distance in t inside the best sample's bracket.  Axis ratios
// 1, 10, 100, 1e3, 1e4, rotated frames, points near and far, near the axes
// (where the secular equation is hardest).  Checks ||P(y) - y_bf|| <= 1e-10
// (relative to the larger semi-axis) and that P(y) is never farther from y
// than the brute-force point.
#include "planted_problems.h"

#include <qp/separable_set.h>

using namespace qptest;
using Vec = dealii::Vector<double>;

namespace
{
  // nearest point of the axis-aligned ellipse boundary to (y1, y2)
  void
  brute_force(const double a,
              const double b,
              const double y1,
              const double y2,
              double      &z1,
              double      &z2)
  {
    const auto dist2 = [&](const double t)
    {
      const double d1 = a * std::cos(t) - y1, d2 = b * std::sin(t) - y2;
      return d1 * d1 + d2 * d2;
    };
    // derivative of dist2 / 2
    const auto deriv = [&](const double t)
    {
      const double c = std::cos(t), s = std::sin(t);
      return (b * b - a * a) * s * c + a * y1 * s - b * y2 * c;
    };
    const unsigned int N      = 400000;
    const double       two_pi = 6.283185307179586;
    unsigned int       best   = 0;
    double             best_d = dist2(0.);
    for (unsigned int k = 1; k < N; ++k)
    {
      const double d = dist2(two_pi * k / N);
      if (d < best_d)
      {
        best_d = d;
        best   = k;
      }
    }
    double lo = two_pi * (best - 1.) / N, hi = two_pi * (best + 1.) / N;
    double t = two_pi * best / N;
    if (deriv(lo) < 0. && deriv(hi) > 0.)
    {
      for (unsigned int it = 0; it < 200; ++it)
      {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi)
          break;
        (deriv(mid) < 0. ? lo : hi) = mid;
      }
      t = 0.5 * (lo + hi);
    }
    z1 = a * std::cos(t);
    z2 = b * std::sin(t);
  }
} // namespace

int
main()
{
  Checker check;
  check.verbose = false;
  std::mt19937                           rng(2024);
  std::uniform_real_distribution<double> u(0., 1.);
  for (const double ratio : {1., 10., 100., 1e3, 1e4})
  {
    double       worst = 0., worst_excess = 0.;
    unsigned int n = 0;
    for (unsigned int trial = 0; trial < 60; ++trial)
    {
      const double a     = 1.;
      const double b     = 1. / ratio;
      const double angle = (trial % 3 == 0) ? 0. : 6.2831853 * u(rng);
      // local point outside: various regimes
      double       y1, y2;
      const double th = 6.283185307179586 * u(rng);
      switch (trial % 5)
      {
        case 0: // far
          y1 = 10. * std::cos(th);
          y2 = 10. * std::sin(th);
          break;
        case 1: // just outside
          y1 = 1.001 * a * std::cos(th);
          y2 = 1.001 * b * std::sin(th);
          break;
        case 2: // near the long axis, beyond the tip
          y1 = a * (1. + u(rng));
          y2 = 1e-3 * b * (u(rng) - 0.5);
          break;
        case 3: // above the flat side
          y1 = a * (2. * u(rng) - 1.);
          y2 = b * (1. + 10. * u(rng));
          break;
        default: // moderate distance
          y1 = 2. * std::cos(th);
          y2 = 2. * b * std::sin(th) + 0.1 * std::sin(th);
          break;
      }
      if (y1 * y1 / (a * a) + y2 * y2 / (b * b) <= 1.)
        continue;
      // the same through the set (global frame)
      const double c = std::cos(angle), s = std::sin(angle);
      Vec          x(2);
      x[0] = c * y1 - s * y2;
      x[1] = s * y1 + c * y2;
      dualcontact::qp::SeparableSet<Vec> set;
      set.add_ellipse(0, a, b, angle);
      set.finalize(x);
      Vec p(x);
      set.project(p);
      double z1, z2;
      brute_force(a, b, y1, y2, z1, z2);
      const double q1 = c * z1 - s * z2, q2 = s * z1 + c * z2;
      const double err = std::hypot(p[0] - q1, p[1] - q2) / a;
      worst            = std::max(worst, err);
      const double dp  = std::hypot(p[0] - x[0], p[1] - x[1]);
      const double dq  = std::hypot(q1 - x[0], q2 - x[1]);
      worst_excess     = std::max(worst_excess, (dp - dq) / (1. + dq));
      ++n;
      check.check(err <= 1e-10,
                  "ratio " + sci(ratio) + " trial " + std::to_string(trial) +
                    ": error " + sci(err));
    }
    check.verbose = true;
    check.check(worst <= 1e-10,
                "axis ratio " + sci(ratio) + ": " + std::to_string(n) +
                  " points, worst |P(y) - brute force| = " + sci(worst));
    check.check(worst_excess <= 1e-14,
                "axis ratio " + sci(ratio) +
                  ": never farther than brute force (worst excess " +
                  sci(worst_excess) + ")");
    check.verbose = false;
  }
  return check.finish("ellipse_projection");
}
