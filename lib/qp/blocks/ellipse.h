/**
 * @file ellipse.h
 * The block kind (y_1/a)^2 + (y_2/b)^2 <= 1, y the pair (x_f, x_{f+1}) in a
 * rotated frame.
 */
#ifndef dualcontact_qp_blocks_ellipse_h
#define dualcontact_qp_blocks_ellipse_h

#include <qp/block_type.h>
#include <qp/blocks/step_length.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dualcontact
{
  namespace qp
  {
    namespace blocks
    {
      /**
       * An ellipse (y_1/a)^2 + (y_2/b)^2 <= 1 with y = R(-angle) x in the
       * local frame (semi-axis a along the direction at the angle, a, b >
       * 0): the 3D slip bound of anisotropic friction.  Active (thesis
       * 1.30) when 1 - ||x||_E <= tol, ||.||_E the norm whose unit ball is
       * the ellipse.
       */
      class Ellipse
      {
      public:
        static constexpr BlockType    type         = BlockType::ellipse;
        static constexpr unsigned int n_components = 2;

        /// What the active-set test found.
        struct State
        {
          bool active;
        };

        double a, b, cos_angle, sin_angle;

        /// (x1, x2) in the local frame
        void
        to_local(const double x1, const double x2, double &y1, double &y2) const
        {
          y1 = cos_angle * x1 + sin_angle * x2;
          y2 = -sin_angle * x1 + cos_angle * x2;
        }

        /// (y1, y2) of the local frame in the global one
        void
        to_global(const double y1,
                  const double y2,
                  double      &x1,
                  double      &x2) const
        {
          x1 = cos_angle * y1 - sin_angle * y2;
          x2 = sin_angle * y1 + cos_angle * y2;
        }

        /// ||(x1, x2)||_E
        double
        norm(const double x1, const double x2) const
        {
          double y1, y2;
          to_local(x1, x2, y1, y2);
          return std::sqrt(square(y1 / a) + square(y2 / b));
        }

        /// (p1, p2) := P(x1, x2), the Euclidean projection
        void
        project(const double x1, const double x2, double &p1, double &p2) const
        {
          double y1, y2;
          to_local(x1, x2, y1, y2);
          if (square(y1 / a) + square(y2 / b) <= 1.)
          {
            p1 = x1;
            p2 = x2;
            return;
          }
          double z1, z2;
          project_axis_aligned(a, b, y1, y2, z1, z2);
          to_global(z1, z2, p1, p2);
        }

        /// unit outward normal at (x1, x2) (on or near the boundary); 0 at
        /// the centre
        void
        normal(const double x1, const double x2, double &n1, double &n2) const
        {
          double y1, y2;
          to_local(x1, x2, y1, y2);
          const double m1 = y1 / (a * a), m2 = y2 / (b * b);
          const double m = std::sqrt(m1 * m1 + m2 * m2);
          if (m == 0.)
          {
            n1 = n2 = 0.;
            return;
          }
          to_global(m1 / m, m2 / m, n1, n2);
        }

        /**
         * Euclidean projection of y (outside the ellipse with semi-axes a,
         * b along the coordinate axes) onto it.  The minimiser is z_i =
         * a_i^2 y_i / (a_i^2 + t) with t >= 0 the root of the secular
         * equation F(t) = sum (a_i y_i / (a_i^2 + t))^2 - 1 = 0.  F is
         * convex and decreasing on t >= 0, so Newton's method started left
         * of the root increases monotonically to it; it is safeguarded by
         * the bracket [t_lo, t_hi] (bisection when a step leaves it), with
         * t_lo = max(0, a_i |y_i| - a_i^2) (F > 0 there) and t_hi = ||(a
         * y1, b y2)|| (F <= 0 there).
         */
        static void
        project_axis_aligned(const double a,
                             const double b,
                             const double y1,
                             const double y2,
                             double      &z1,
                             double      &z2)
        {
          constexpr double epsilon = std::numeric_limits<double>::epsilon();
          const double     ay1 = a * std::abs(y1), by2 = b * std::abs(y2);
          double           lo = std::max({0., ay1 - a * a, by2 - b * b});
          double           hi = std::sqrt(ay1 * ay1 + by2 * by2);
          double           t  = lo;
          for (unsigned int it = 0; it < 200; ++it)
          {
            const double r1 = ay1 / (a * a + t), r2 = by2 / (b * b + t);
            const double F = r1 * r1 + r2 * r2 - 1.;
            if (F > 0.)
              lo = t;
            else if (F < 0.)
              hi = t;
            else
              break;
            // F'(t) = -2 (r1^2/(a^2+t) + r2^2/(b^2+t))
            const double dF =
              -2. * (r1 * r1 / (a * a + t) + r2 * r2 / (b * b + t));
            double t_new = (dF < 0.) ? t - F / dF : 0.5 * (lo + hi);
            if (!(t_new > lo && t_new < hi))
              t_new = 0.5 * (lo + hi);
            if (std::abs(t_new - t) <= 2. * epsilon * std::max(t_new, 1e-300) ||
                hi - lo <= 2. * epsilon * hi)
            {
              t = t_new;
              break;
            }
            t = t_new;
          }
          z1 = a * a * y1 / (a * a + t);
          z2 = b * b * y2 / (b * b + t);
          // rounding may leave z a hair outside: scale onto the set
          const double q = std::sqrt(square(z1 / a) + square(z2 / b));
          if (q > 1.)
          {
            z1 /= q;
            z2 /= q;
          }
        }

        State
        classify(const double *x, const double tolerance) const
        {
          return {1. - norm(x[0], x[1]) <= tolerance};
        }

        /// x := P(x)
        void
        project(double *x) const
        {
          project(x[0], x[1], x[0], x[1]);
        }

        /// ||x - P(x)||^2
        double
        distance_squared(const double *x) const
        {
          double p1, p2;
          project(x[0], x[1], p1, p2);
          return square(x[0] - p1) + square(x[1] - p2);
        }

        /// The largest alpha with ||x - alpha p||_E <= 1.
        double
        max_step(const double *x, const double *p) const
        {
          double y1, y2, q1, q2;
          to_local(x[0], x[1], y1, y2);
          to_local(p[0], p[1], q1, q2);
          const double ia2 = 1. / (a * a), ib2 = 1. / (b * b);
          return positive_root(q1 * q1 * ia2 + q2 * q2 * ib2,
                               y1 * q1 * ia2 + y2 * q2 * ib2,
                               y1 * y1 * ia2 + y2 * y2 * ib2 - 1.);
        }

        /// x := P(x - alpha p) (rounding may leave x - alpha p a hair
        /// outside for alpha = max_step())
        void
        feasible_step(double *x, const double *p, const double alpha) const
        {
          x[0] -= alpha * p[0];
          x[1] -= alpha * p[1];
          project(x);
        }

        /// beta = g - min(n'g, 0) n of an active ellipse (thesis 1.31)
        void
        chopped_gradient(const double *x,
                         const double *g,
                         const State &,
                         double *beta) const
        {
          double n0, n1;
          normal(x[0], x[1], n0, n1);
          const double ng = n0 * g[0] + n1 * g[1];
          const double c  = std::min(ng, 0.);
          beta[0]         = g[0] - c * n0;
          beta[1]         = g[1] - c * n1;
        }

        /// The reduced chopped gradient of an active ellipse (thesis
        /// 1.4.3): g where n'g > 0 (-g points into the ellipse), else
        /// (x - P(x - alpha g)) / alpha.
        void
        reduced_chopped_gradient(const double *x,
                                 const double *g,
                                 const double  alpha,
                                 const State &,
                                 double *reduced) const
        {
          double n0, n1;
          normal(x[0], x[1], n0, n1);
          if (n0 * g[0] + n1 * g[1] > 0.)
          {
            reduced[0] = g[0];
            reduced[1] = g[1];
            return;
          }
          double z0, z1;
          project(x[0] - alpha * g[0], x[1] - alpha * g[1], z0, z1);
          reduced[0] = (x[0] - z0) / alpha;
          reduced[1] = (x[1] - z1) / alpha;
        }

        /// The multiplier estimate max(-n'g, 0) times the distance to the
        /// boundary, both at the radial point x / ||x||_E (an approximation
        /// of the nearest one).
        double
        complementarity(const double *x, const double *g) const
        {
          const double q = norm(x[0], x[1]);
          if (!(q > 0.))
            return 0.;
          double n0, n1;
          normal(x[0] / q, x[1] / q, n0, n1);
          const double dist =
            std::abs(1. - 1. / q) * std::sqrt(x[0] * x[0] + x[1] * x[1]);
          return std::max(-(n0 * g[0] + n1 * g[1]), 0.) * dist;
        }
      };
    } // namespace blocks
  }   // namespace qp
} // namespace dualcontact

#endif
