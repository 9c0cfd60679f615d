/**
 * @file bound.h
 * The block kind x_i >= l.
 */
#ifndef dualcontact_qp_blocks_bound_h
#define dualcontact_qp_blocks_bound_h

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
       * A lower bound x_i >= l: the normal contact multipliers, the
       * membrane's unknowns.  Active (thesis 1.30) when x_i - l <= tol |l|
       * (exactly x_i = l when l = 0); the outward normal is -1, so the
       * chopped gradient is min(g, 0) (thesis 1.31).
       *
       * The set's passes over runs of consecutive bounds are VectorKernels'
       * (the same expressions four or eight entries at a time;
       * tests/qp/vector_kernels checks them bitwise against these
       * functions); these serve everything else.  The operations of every
       * kind are listed in qp/blocks/README.md.
       */
      class Bound
      {
      public:
        static constexpr BlockType    type         = BlockType::bound;
        static constexpr unsigned int n_components = 1;

        /// What the active-set test found.
        struct State
        {
          bool active;
        };

        double lower;

        State
        classify(const double *x, const double tolerance) const
        {
          return {x[0] - lower <= tolerance * std::abs(lower)};
        }

        /// x := P(x)
        void
        project(double *x) const
        {
          x[0] = std::max(x[0], lower);
        }

        /// ||x - P(x)||^2
        double
        distance_squared(const double *x) const
        {
          return square(std::min(x[0] - lower, 0.));
        }

        /// The largest alpha with x - alpha p feasible, (x - l) / p for
        /// p > 0, offered to @p ratio.
        void
        offer_step(const double *x, const double *p, MinRatio &ratio) const
        {
          ratio.offer(std::max(x[0] - lower, 0.), p[0]);
        }

        /// x := x - alpha p for alpha up to the largest feasible step, put
        /// on l when it lands there (lands_on()) or beyond.
        void
        feasible_step(double *x, const double *p, const double alpha) const
        {
          const double y = x[0] - alpha * p[0];
          const double scale =
            std::abs(y) + std::abs(alpha * p[0]) + std::abs(lower);
          x[0] = (y < lower || lands_on(y, lower, scale)) ? lower : y;
        }

        /// beta = min(g, 0) of an active bound (thesis 1.31)
        void
        chopped_gradient(const double *,
                         const double *g,
                         const State &,
                         double *beta) const
        {
          beta[0] = std::min(g[0], 0.);
        }

        /// The reduced chopped gradient of an active bound (thesis 1.4.3):
        /// g where g < 0 (the step leaves the bound), else
        /// (x - max(l, x - alpha g)) / alpha.
        void
        reduced_chopped_gradient(const double *x,
                                 const double *g,
                                 const double  alpha,
                                 const State &,
                                 double *reduced) const
        {
          reduced[0] = g[0] < 0. ?
                         g[0] :
                         (x[0] - std::max(lower, x[0] - alpha * g[0])) / alpha;
        }

        /// The multiplier estimate max(g, 0) times the distance |x - l|.
        double
        complementarity(const double *x, const double *g) const
        {
          return std::max(g[0], 0.) * std::abs(x[0] - lower);
        }
      };
    } // namespace blocks
  }   // namespace qp
} // namespace dualcontact

#endif
