/**
 * @file box.h
 * The block kind l <= x_i <= u.
 */
#ifndef dualcontact_qp_blocks_box_h
#define dualcontact_qp_blocks_box_h

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
       * A box l <= x_i <= u (l = u allowed): the 2D Tresca slip bounds.
       * Active (thesis 1.30) at l when x_i - l <= tol |l|, at u when u - x_i
       * <= tol |u|; l = u is always active at both.  The outward normal is
       * -1 at l and +1 at u, so the chopped gradient (thesis 1.31) is
       * min(g, 0) at l, max(g, 0) at u and 0 at both.
       */
      class Box
      {
      public:
        static constexpr BlockType    type         = BlockType::box;
        static constexpr unsigned int n_components = 1;

        /// What the active-set test found.
        struct State
        {
          bool at_lower, at_upper, active;
        };

        double lower, upper;

        State
        classify(const double *x, const double tolerance) const
        {
          const bool at_l = x[0] - lower <= tolerance * std::abs(lower);
          const bool at_u = upper - x[0] <= tolerance * std::abs(upper);
          return {at_l, at_u, at_l || at_u};
        }

        /// x := P(x)
        void
        project(double *x) const
        {
          x[0] = std::min(std::max(x[0], lower), upper);
        }

        /// ||x - P(x)||^2
        double
        distance_squared(const double *x) const
        {
          const double y = x[0];
          return square(y - std::min(std::max(y, lower), upper));
        }

        /// The largest alpha with x - alpha p feasible, (x - l) / p for
        /// p > 0 and (u - x) / |p| for p < 0, offered to @p ratio.
        void
        offer_step(const double *x, const double *p, MinRatio &ratio) const
        {
          const double room =
            p[0] > 0. ? std::max(x[0] - lower, 0.) : std::max(upper - x[0], 0.);
          ratio.offer(room, std::abs(p[0]));
        }

        /// x := x - alpha p for alpha up to the largest feasible step, put
        /// on l or u when it lands there (lands_on()) or beyond.
        void
        feasible_step(double *x, const double *p, const double alpha) const
        {
          const double y     = x[0] - alpha * p[0];
          const double scale = std::abs(y) + std::abs(alpha * p[0]) +
                               std::abs(lower) + std::abs(upper);
          if (y < lower || lands_on(y, lower, scale))
            x[0] = lower;
          else if (y > upper || lands_on(y, upper, scale))
            x[0] = upper;
          else
            x[0] = y;
        }

        /// beta of the box in @p state (thesis 1.31); 0 when it is free.
        void
        chopped_gradient(const double *,
                         const double *g,
                         const State  &state,
                         double       *beta) const
        {
          beta[0] =
            (state.at_lower && state.at_upper) ?
              0. :
              (state.at_lower ? std::min(g[0], 0.) :
                                (state.at_upper ? std::max(g[0], 0.) : 0.));
        }

        /// The reduced chopped gradient of an active box (thesis 1.4.3):
        /// g where -g points into the box, else (x - P(x - alpha g)) /
        /// alpha.
        void
        reduced_chopped_gradient(const double *x,
                                 const double *g,
                                 const double  alpha,
                                 const State  &state,
                                 double       *reduced) const
        {
          const bool inward = !(state.at_lower && state.at_upper) &&
                              (state.at_lower ? g[0] < 0. : g[0] > 0.);
          if (inward)
            reduced[0] = g[0];
          else
          {
            double z = x[0] - alpha * g[0];
            project(&z);
            reduced[0] = (x[0] - z) / alpha;
          }
        }

        /// The multiplier estimate at the nearer bound times the distance
        /// to it.
        double
        complementarity(const double *x, const double *g) const
        {
          const double y = x[0];
          if (y - lower <= upper - y)
            return std::max(g[0], 0.) * std::abs(y - lower);
          return std::max(-g[0], 0.) * std::abs(upper - y);
        }
      };
    } // namespace blocks
  }   // namespace qp
} // namespace dualcontact

#endif
