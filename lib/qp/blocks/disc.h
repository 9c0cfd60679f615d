/**
 * @file disc.h
 * The block kind ||(x_f, x_{f+1})|| <= r.
 */
#ifndef dualcontact_qp_blocks_disc_h
#define dualcontact_qp_blocks_disc_h

#include <qp/block_type.h>
#include <qp/blocks/step_length.h>

#include <algorithm>
#include <cmath>

namespace dualcontact
{
  namespace qp
  {
    namespace blocks
    {
      /**
       * A disc ||(x_f, x_{f+1})|| <= r (r >= 0): the 3D Tresca slip bound
       * of a contact node's two tangential multipliers.  Active (thesis
       * 1.30) when r - ||x|| <= tol r; the outward normal is x / ||x||.
       * With r = 0 the set is a point: always active, chopped gradient 0.
       */
      class Disc
      {
      public:
        static constexpr BlockType    type         = BlockType::disc;
        static constexpr unsigned int n_components = 2;

        /// What the active-set test found.
        struct State
        {
          bool active;
        };

        double radius;

        State
        classify(const double *x, const double tolerance) const
        {
          return {radius - std::sqrt(x[0] * x[0] + x[1] * x[1]) <=
                  tolerance * radius};
        }

        /// x := P(x), the radial projection
        void
        project(double *x) const
        {
          const double n = std::sqrt(x[0] * x[0] + x[1] * x[1]);
          if (n > radius)
          {
            const double s = radius / n;
            x[0] *= s;
            x[1] *= s;
          }
        }

        /// ||x - P(x)||^2
        double
        distance_squared(const double *x) const
        {
          const double n = std::sqrt(x[0] * x[0] + x[1] * x[1]);
          return square(std::max(n - radius, 0.));
        }

        /// The largest alpha with ||x - alpha p|| <= r.
        double
        max_step(const double *x, const double *p) const
        {
          return positive_root(p[0] * p[0] + p[1] * p[1],
                               x[0] * p[0] + x[1] * p[1],
                               x[0] * x[0] + x[1] * x[1] - radius * radius);
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

        /// beta = g - min(n'g, 0) n of an active disc (thesis 1.31)
        void
        chopped_gradient(const double *x,
                         const double *g,
                         const State &,
                         double *beta) const
        {
          const double n = std::sqrt(x[0] * x[0] + x[1] * x[1]);
          if (n == 0.) // radius 0: the set is a point
          {
            beta[0] = beta[1] = 0.;
            return;
          }
          const double n0 = x[0] / n, n1 = x[1] / n;
          const double ng = n0 * g[0] + n1 * g[1];
          const double c  = std::min(ng, 0.);
          beta[0]         = g[0] - c * n0;
          beta[1]         = g[1] - c * n1;
        }

        /// The reduced chopped gradient of an active disc (thesis 1.4.3):
        /// g where n'g > 0 (-g points into the disc), else
        /// (x - P(x - alpha g)) / alpha.
        void
        reduced_chopped_gradient(const double *x,
                                 const double *g,
                                 const double  alpha,
                                 const State &,
                                 double *reduced) const
        {
          const double n = std::sqrt(x[0] * x[0] + x[1] * x[1]);
          if (n != 0. && (x[0] / n) * g[0] + (x[1] / n) * g[1] > 0.)
          {
            reduced[0] = g[0];
            reduced[1] = g[1];
            return;
          }
          double z[2] = {x[0] - alpha * g[0], x[1] - alpha * g[1]};
          project(z);
          reduced[0] = (x[0] - z[0]) / alpha;
          reduced[1] = (x[1] - z[1]) / alpha;
        }

        /// The multiplier estimate max(-n'g, 0) times the distance
        /// |r - ||x||| to the circle.
        double
        complementarity(const double *x, const double *g) const
        {
          const double n = std::sqrt(x[0] * x[0] + x[1] * x[1]);
          if (n > 0.)
            return std::max(-(x[0] * g[0] + x[1] * g[1]) / n, 0.) *
                   std::abs(radius - n);
          return 0.;
        }
      };
    } // namespace blocks
  }   // namespace qp
} // namespace dualcontact

#endif
