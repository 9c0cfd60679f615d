/**
 * @file cone.h
 * The block kind ||(x_{f+1}, x_{f+2})|| <= mu x_f.
 */
#ifndef dualcontact_qp_blocks_cone_h
#define dualcontact_qp_blocks_cone_h

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
       * A second-order cone ||x_t|| <= mu x_n, x_n = x_f the normal
       * component, x_t = (x_{f+1}, x_{f+2}) the tangential ones (mu >= 0):
       * a contact node's multipliers with Coulomb friction.  Active (thesis
       * 1.30) on the smooth boundary when mu x_n - ||x_t|| <= tol ||x||,
       * and at the apex when x_n <= 0, where the normal is not unique and
       * the chopped gradient is -P_K(-g) (K the cone, its own tangent cone
       * there).
       */
      class Cone
      {
      public:
        static constexpr BlockType    type         = BlockType::cone;
        static constexpr unsigned int n_components = 3;

        /// What the active-set test found.
        struct State
        {
          bool active, apex;
        };

        double mu;

        State
        classify(const double *x, const double tolerance) const
        {
          const double rt = std::sqrt(x[1] * x[1] + x[2] * x[2]);
          if (x[0] <= 0.)
            return {true, true};
          const double norm = std::sqrt(x[0] * x[0] + rt * rt);
          return {mu * x[0] - rt <= tolerance * norm, false};
        }

        /// z := P(x) (@p z must not be @p x)
        void
        project(const double *x, double *z) const
        {
          const double rt = std::sqrt(x[1] * x[1] + x[2] * x[2]);
          if (mu * x[0] >= rt)
          {
            z[0] = x[0];
            z[1] = x[1];
            z[2] = x[2];
            return;
          }
          if (mu * rt <= -x[0])
          {
            z[0] = z[1] = z[2] = 0.;
            return;
          }
          // here rt > 0
          const double s = (x[0] + mu * rt) / (mu * mu + 1.);
          z[0]           = s;
          z[1]           = mu * s * x[1] / rt;
          z[2]           = mu * s * x[2] / rt;
        }

        /// x := P(x)
        void
        project(double *x) const
        {
          const double c[3] = {x[0], x[1], x[2]};
          project(c, x);
        }

        /// ||x - P(x)||^2
        double
        distance_squared(const double *x) const
        {
          double z[3];
          project(x, z);
          return square(x[0] - z[0]) + square(x[1] - z[1]) +
                 square(x[2] - z[2]);
        }

        /// The largest alpha with x - alpha p in the cone.
        double
        max_step(const double *y, const double *q) const
        {
          constexpr double infinity = std::numeric_limits<double>::infinity();
          // feasible: mu (y0 - a q0) >= ||yt - a qt||, i.e. h(a) =
          // ||yt - a qt||^2 - mu^2 (y0 - a q0)^2 <= 0 and y0 - a q0 >= 0.
          // Both are convex/linear pieces of the convex cone's boundary
          // along a line: the feasible alphas form an interval [0, a*].
          double a_lin = infinity; // y0 - a q0 >= 0
          if (q[0] > 0.)
            a_lin = std::max(y[0], 0.) / q[0];
          const double A   = q[1] * q[1] + q[2] * q[2] - mu * mu * q[0] * q[0];
          const double B   = y[1] * q[1] + y[2] * q[2] - mu * mu * y[0] * q[0];
          const double C   = y[1] * y[1] + y[2] * y[2] - mu * mu * y[0] * y[0];
          double       a_q = infinity;
          if (A > 0.)
            a_q = positive_root(A, B, C);
          else if (A < 0.)
          {
            // concave quadratic: h(a) = A a^2 - 2 B a + C > 0 only
            // between its roots; the step ends at the first alpha > 0
            // where h turns from <= 0 to > 0.
            const double disc = B * B - A * std::min(C, 0.);
            if (disc > 0.)
            {
              const double s  = std::sqrt(disc);
              const double r1 = (B - s) / A, r2 = (B + s) / A;
              const double rl = std::min(r1, r2), rh = std::max(r1, r2);
              if (rh > 0.)
                a_q = std::max(rl, 0.);
            }
          }
          else if (B < 0.) // linear: h(a) = -2 B a + C, increasing
            a_q = std::max(-C, 0.) / (-2. * B);
          return std::min(a_lin, a_q);
        }

        /// x := P(x - alpha p) (rounding may leave x - alpha p a hair
        /// outside for alpha = max_step())
        void
        feasible_step(double *x, const double *p, const double alpha) const
        {
          x[0] -= alpha * p[0];
          x[1] -= alpha * p[1];
          x[2] -= alpha * p[2];
          project(x);
        }

        /// beta of an active cone (thesis 1.31): g - min(n'g, 0) n on the
        /// smooth boundary, -P_K(-g) at the apex
        void
        chopped_gradient(const double *x,
                         const double *g,
                         const State  &state,
                         double       *beta) const
        {
          if (state.apex)
          {
            const double mg[3] = {-g[0], -g[1], -g[2]};
            double       z[3];
            project(mg, z);
            beta[0] = -z[0];
            beta[1] = -z[1];
            beta[2] = -z[2];
            return;
          }
          const double rt = std::sqrt(x[1] * x[1] + x[2] * x[2]);
          if (rt == 0.)
          {
            // a ray (mu = 0): only moves along the normal axis remain
            beta[0] = g[0];
            beta[1] = beta[2] = 0.;
            return;
          }
          const double inv  = 1. / std::sqrt(1. + mu * mu);
          const double n[3] = {-mu * inv, x[1] / rt * inv, x[2] / rt * inv};
          const double ng   = n[0] * g[0] + n[1] * g[1] + n[2] * g[2];
          const double c    = std::min(ng, 0.);
          beta[0]           = g[0] - c * n[0];
          beta[1]           = g[1] - c * n[1];
          beta[2]           = g[2] - c * n[2];
        }

        /// Does -g point into the cone at an active x (the "n'g > 0" test
        /// of the reduced chopped gradient)?
        bool
        points_inward(const double *x,
                      const double *g,
                      const State  &state) const
        {
          if (state.apex)
          {
            const double mg[3] = {-g[0], -g[1], -g[2]};
            return mu * mg[0] >= std::sqrt(mg[1] * mg[1] + mg[2] * mg[2]);
          }
          const double rt = std::sqrt(x[1] * x[1] + x[2] * x[2]);
          if (rt == 0.)
            return g[1] == 0. && g[2] == 0. && g[0] <= 0.;
          const double ng = -mu * g[0] + (x[1] * g[1] + x[2] * g[2]) / rt;
          return ng > 0.;
        }

        /// The reduced chopped gradient of an active cone (thesis 1.4.3):
        /// g where -g points into the cone, else (x - P(x - alpha g)) /
        /// alpha.
        void
        reduced_chopped_gradient(const double *x,
                                 const double *g,
                                 const double  alpha,
                                 const State  &state,
                                 double       *reduced) const
        {
          if (points_inward(x, g, state))
          {
            reduced[0] = g[0];
            reduced[1] = g[1];
            reduced[2] = g[2];
            return;
          }
          const double w[3] = {x[0] - alpha * g[0],
                               x[1] - alpha * g[1],
                               x[2] - alpha * g[2]};
          double       z[3];
          project(w, z);
          for (unsigned int c = 0; c < 3; ++c)
            reduced[c] = (x[c] - z[c]) / alpha;
        }

        /// The multiplier estimate max(-n'g, 0) times the distance to the
        /// boundary (on the axis with the worst normal, the one against
        /// g_t).
        double
        complementarity(const double *x, const double *g) const
        {
          const double rt  = std::sqrt(x[1] * x[1] + x[2] * x[2]);
          const double inv = 1. / std::sqrt(1. + mu * mu);
          if (rt > 0.)
          {
            const double ng =
              (-mu * g[0] + (x[1] * g[1] + x[2] * g[2]) / rt) * inv;
            return std::max(-ng, 0.) * std::abs(mu * x[0] - rt) * inv;
          }
          if (x[0] > 0.)
          {
            const double gt = std::sqrt(g[1] * g[1] + g[2] * g[2]);
            const double ng = (-mu * g[0] - gt) * inv;
            return std::max(-ng, 0.) * mu * x[0] * inv;
          }
          return 0.;
        }
      };
    } // namespace blocks
  }   // namespace qp
} // namespace dualcontact

#endif
