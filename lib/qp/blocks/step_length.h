/**
 * @file step_length.h
 * What the block kinds share for their largest feasible step (the CG
 * half-step's alpha_f, thesis 2.4) and for landing on their boundary.
 */
#ifndef dualcontact_qp_blocks_step_length_h
#define dualcontact_qp_blocks_step_length_h

#include <algorithm>
#include <cmath>
#include <limits>

namespace dualcontact
{
  namespace qp
  {
    namespace blocks
    {
      /// v^2
      inline double
      square(const double v)
      {
        return v * v;
      }

      /**
       * Largest alpha >= 0 with q(alpha) = A alpha^2 - 2 B alpha + C <= 0,
       * where C <= 0 (the start is feasible) and A >= 0: the positive root,
       * in the form without cancellation; +infinity when A <= 0.  The step
       * of a disc, an ellipse and the quadratic part of a cone.
       */
      inline double
      positive_root(const double A, const double B, double C)
      {
        if (A <= 0.)
          return std::numeric_limits<double>::infinity();
        C              = std::min(C, 0.);
        const double d = std::sqrt(std::max(B * B - A * C, 0.));
        if (B >= 0.)
          return (B + d) / A;
        return (d - B) > 0. ? -C / (d - B) : 0.;
      }

      /**
       * The smallest ratio room/q over q > 0 (the largest feasible step of
       * a bound or box along -q), tracked as a fraction compared by
       * cross-multiplication: no division per entry, no branch.  It works
       * on a lane of VectorKernels::RatioLanes, whose kernels follow the
       * same rule for the runs of bounds.
       */
      struct MinRatio
      {
        double &num, &den;

        void
        offer(const double room, const double q)
        {
          const bool take = q > 0. && room * den < num * q;
          num             = take ? room : num;
          den             = take ? q : den;
        }
      };

      /**
       * Does a step's end @p y count as landing on @p bound?  The step
       * length was computed in rounding arithmetic, so a block meant to
       * land on its bound may miss it by a few ulps of the quantities
       * involved (their magnitudes summed in @p scale); it is put on the
       * bound, or it would not count as active.
       */
      inline bool
      lands_on(const double y, const double bound, const double scale)
      {
        return std::abs(y - bound) <=
               8. * std::numeric_limits<double>::epsilon() * scale;
      }
    } // namespace blocks
  }   // namespace qp
} // namespace dualcontact

#endif
