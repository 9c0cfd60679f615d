#include <qp/separable_set.h>
#include <qp/vector_helpers.h>
#include <qp/vector_kernels.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <type_traits>

namespace dualcontact
{
  namespace qp
  {
    const char *
    block_type_name(const BlockType type)
    {
      switch (type)
      {
        case BlockType::bound:
          return "bound";
        case BlockType::box:
          return "box";
        case BlockType::disc:
          return "disc";
        case BlockType::ellipse:
          return "ellipse";
        case BlockType::cone:
          return "cone";
      }
      return "unknown";
    }


    namespace
    {
      constexpr double infinity = std::numeric_limits<double>::infinity();
      constexpr double epsilon  = std::numeric_limits<double>::epsilon();

      inline double
      sq(const double v)
      {
        return v * v;
      }

      // Largest alpha >= 0 with q(alpha) = A alpha^2 - 2 B alpha + C <= 0,
      // where C <= 0 (the start is feasible) and A >= 0: the positive root,
      // in the form without cancellation.
      inline double
      positive_root(const double A, const double B, double C)
      {
        if (A <= 0.)
          return infinity;
        C              = std::min(C, 0.);
        const double d = std::sqrt(std::max(B * B - A * C, 0.));
        if (B >= 0.)
          return (B + d) / A;
        return (d - B) > 0. ? -C / (d - B) : 0.;
      }

      // ---------------- ellipse ------------------------------------------
      // Local frame: y = R(-angle) x, the set (y1/a)^2 + (y2/b)^2 <= 1.

      /**
       * Euclidean projection of y (outside the ellipse with semi-axes a, b
       * along the coordinate axes) onto it.  The minimiser is z_i =
       * a_i^2 y_i / (a_i^2 + t) with t >= 0 the root of the secular
       * equation F(t) = sum (a_i y_i / (a_i^2 + t))^2 - 1 = 0.  F is convex
       * and decreasing on t >= 0, so Newton's method started left of the
       * root increases monotonically to it; it is safeguarded by the
       * bracket [t_lo, t_hi] (bisection when a step leaves it), with
       * t_lo = max(0, a_i |y_i| - a_i^2) (F > 0 there) and
       * t_hi = ||(a y1, b y2)|| (F <= 0 there).
       */
      inline void
      project_ellipse_local(const double a,
                            const double b,
                            const double y1,
                            const double y2,
                            double      &z1,
                            double      &z2)
      {
        const double ay1 = a * std::abs(y1), by2 = b * std::abs(y2);
        double       lo = std::max({0., ay1 - a * a, by2 - b * b});
        double       hi = std::sqrt(ay1 * ay1 + by2 * by2);
        double       t  = lo;
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
        const double q = std::sqrt(sq(z1 / a) + sq(z2 / b));
        if (q > 1.)
        {
          z1 /= q;
          z2 /= q;
        }
      }

      struct EllipseFrame
      {
        double a, b, c, s;
        // to the local frame
        inline void
        to_local(const double x1, const double x2, double &y1, double &y2) const
        {
          y1 = c * x1 + s * x2;
          y2 = -s * x1 + c * x2;
        }
        inline void
        to_global(const double y1,
                  const double y2,
                  double      &x1,
                  double      &x2) const
        {
          x1 = c * y1 - s * y2;
          x2 = s * y1 + c * y2;
        }
        inline double
        enorm(const double x1, const double x2) const
        {
          double y1, y2;
          to_local(x1, x2, y1, y2);
          return std::sqrt(sq(y1 / a) + sq(y2 / b));
        }
        inline void
        project(const double x1, const double x2, double &p1, double &p2) const
        {
          double y1, y2;
          to_local(x1, x2, y1, y2);
          if (sq(y1 / a) + sq(y2 / b) <= 1.)
          {
            p1 = x1;
            p2 = x2;
            return;
          }
          double z1, z2;
          project_ellipse_local(a, b, y1, y2, z1, z2);
          to_global(z1, z2, p1, p2);
        }
        // unit outward normal at (x1, x2) (on or near the boundary)
        inline void
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
      };

      // ---------------- cone ----------------------------------------------
      inline void
      project_cone(const double mu, const double *x, double *z)
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
    } // namespace


    // ======================== building ==================================

    template <typename VectorType>
    SeparableSet<VectorType>::SeparableSet(const double active_tolerance)
        : tolerance(active_tolerance)
    {
      AssertThrow(active_tolerance >= 0. && active_tolerance < 1.,
                  dealii::ExcMessage(
                    "SeparableSet: the active tolerance must lie in [0, 1)"));
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::add_bound(const size_type first,
                                        const double    lower)
    {
      AssertThrow(std::isfinite(lower),
                  dealii::ExcMessage("bound constraint at unknown " +
                                     std::to_string(first) +
                                     ": the lower bound must be finite"));
      added_bounds.push_back({first, lower});
      finalized = false;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::add_box(const size_type first,
                                      const double    lower,
                                      const double    upper)
    {
      AssertThrow(std::isfinite(lower) && std::isfinite(upper) &&
                    lower <= upper,
                  dealii::ExcMessage(
                    "box constraint at unknown " + std::to_string(first) +
                    ": need finite lower <= upper, got " +
                    std::to_string(lower) + ", " + std::to_string(upper)));
      added_boxes.push_back({first, lower, upper});
      finalized = false;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::add_disc(const size_type first,
                                       const double    radius)
    {
      AssertThrow(std::isfinite(radius) && radius >= 0.,
                  dealii::ExcMessage("disc constraint at unknown " +
                                     std::to_string(first) +
                                     ": the radius must be finite and >= 0"));
      added_discs.push_back({first, radius});
      finalized = false;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::add_ellipse(const size_type first,
                                          const double    a,
                                          const double    b,
                                          const double    angle)
    {
      AssertThrow(std::isfinite(a) && std::isfinite(b) && a > 0. && b > 0. &&
                    std::isfinite(angle),
                  dealii::ExcMessage(
                    "ellipse constraint at unknown " + std::to_string(first) +
                    ": the semi-axes must be finite and positive"));
      added_ellipses.push_back({first, a, b, std::cos(angle), std::sin(angle)});
      finalized = false;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::add_cone(const size_type first, const double mu)
    {
      AssertThrow(std::isfinite(mu) && mu >= 0.,
                  dealii::ExcMessage("cone constraint at unknown " +
                                     std::to_string(first) +
                                     ": mu must be finite and >= 0"));
      added_cones.push_back({first, mu});
      finalized = false;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::finalize(const VectorType &layout)
    {
      owned                        = layout.locally_owned_elements();
      local_size                   = owned.n_elements();
      const size_type            n = layout.size();
      std::vector<unsigned char> used(local_size, 0);
      // one contiguous range (always in serial): membership and local
      // index by arithmetic instead of IndexSet's searches, which were a
      // tenth of a short QP's work on a small problem (fclib's loops
      // finalize a set per QP)
      const bool      contiguous = owned.is_contiguous();
      const size_type begin =
        contiguous && local_size > 0 ? owned.nth_index_in_set(0) : 0;
      const auto is_owned = [&](const size_type i)
      {
        return contiguous ? (i >= begin && i < begin + local_size) :
                            owned.is_element(i);
      };
      const auto local_index = [&](const size_type i) -> size_type
      { return contiguous ? i - begin : owned.index_within_set(i); };

      // Returns true if the block [first, first+width) is locally owned,
      // false if it is owned elsewhere; throws if it straddles, leaves the
      // vector, or overlaps a block already placed.
      const auto place = [&](const size_type    first,
                             const unsigned int width,
                             const char        *type,
                             size_type         &local) -> bool
      {
        AssertThrow(first + width <= n,
                    dealii::ExcMessage(
                      std::string(type) + " block at unknown " +
                      std::to_string(first) + " exceeds the vector size " +
                      std::to_string(n)));
        unsigned int n_owned = 0;
        for (unsigned int k = 0; k < width; ++k)
          n_owned += is_owned(first + k) ? 1 : 0;
        if (n_owned == 0)
          return false;
        AssertThrow(n_owned == width,
                    dealii::ExcMessage(std::string(type) +
                                       " block at unknown " +
                                       std::to_string(first) +
                                       " straddles two MPI ranks; "
                                       "partition so that blocks stay "
                                       "together"));
        local = local_index(first);
        for (unsigned int k = 0; k < width; ++k)
        {
          const size_type l = local_index(first + k);
          AssertThrow(l == local + k,
                      dealii::ExcMessage(
                        std::string(type) + " block at unknown " +
                        std::to_string(first) + " is not contiguous locally"));
          AssertThrow(!used[l],
                      dealii::ExcMessage(std::string(type) +
                                         " block at unknown " +
                                         std::to_string(first) +
                                         " overlaps another block (unknown " +
                                         std::to_string(first + k) + ")"));
          used[l] = 1;
        }
        return true;
      };

      bounds.clear();
      boxes.clear();
      discs.clear();
      ellipses.clear();
      cones.clear();
      size_type local = 0;
      for (const auto &blk : added_bounds)
        if (place(blk.global, 1, "bound", local))
          bounds.push_back({local, blk.lower});
      for (const auto &blk : added_boxes)
        if (place(blk.global, 1, "box", local))
          boxes.push_back({local, blk.lower, blk.upper});
      for (const auto &blk : added_discs)
        if (place(blk.global, 2, "disc", local))
          discs.push_back({local, blk.radius});
      for (const auto &blk : added_ellipses)
        if (place(blk.global, 2, "ellipse", local))
          ellipses.push_back(
            {local, blk.a, blk.b, blk.cos_angle, blk.sin_angle});
      for (const auto &blk : added_cones)
        if (place(blk.global, 3, "cone", local))
          cones.push_back({local, blk.mu});

      // Sorting by offset makes the sweeps stream through memory.
      const auto by_offset = [](const auto &l, const auto &r)
      { return l.global < r.global; };
      std::sort(bounds.begin(), bounds.end(), by_offset);
      std::sort(boxes.begin(), boxes.end(), by_offset);
      std::sort(discs.begin(), discs.end(), by_offset);
      std::sort(ellipses.begin(), ellipses.end(), by_offset);
      std::sort(cones.begin(), cones.end(), by_offset);

      // runs of consecutive bound / box blocks (SoA copies of the bounds)
      const auto make_runs = [](const auto &blocks, std::vector<Run> &runs)
      {
        runs.clear();
        for (std::size_t k = 0; k < blocks.size(); ++k)
          if (!runs.empty() &&
              runs.back().begin + runs.back().count == blocks[k].global)
            ++runs.back().count;
          else
            runs.push_back({static_cast<std::size_t>(blocks[k].global), 1, k});
      };
      make_runs(bounds, bound_runs);
      make_runs(boxes, box_runs);
      bound_lower.resize(bounds.size());
      for (std::size_t k = 0; k < bounds.size(); ++k)
        bound_lower[k] = bounds[k].lower;
      box_lower.resize(boxes.size());
      box_upper.resize(boxes.size());
      for (std::size_t k = 0; k < boxes.size(); ++k)
      {
        box_lower[k] = boxes[k].lower;
        box_upper[k] = boxes[k].upper;
      }
      free_ranges.clear();
      for (std::size_t i = 0; i < local_size; ++i)
        if (!used[i])
        {
          if (!free_ranges.empty() && free_ranges.back().second == i)
            ++free_ranges.back().second;
          else
            free_ranges.emplace_back(i, i + 1);
        }

      const std::array<std::size_t, n_block_types> local_counts = {
        {bounds.size(),
         boxes.size(),
         discs.size(),
         ellipses.size(),
         cones.size()}};
      for (unsigned int t = 0; t < n_block_types; ++t)
        global_counts[t] = static_cast<size_type>(
          internal::sum(static_cast<double>(local_counts[t]), layout) + 0.5);
      finalized = true;
    }


    namespace
    {
      /**
       * Position in @p blocks (sorted by local offset in finalize()) of the
       * block added at global index @p global; blocks.size() if another
       * rank owns it.
       */
      template <typename Block>
      std::size_t
      placed_position(const std::vector<Block>             &blocks,
                      const dealii::IndexSet               &owned,
                      const dealii::types::global_dof_index global)
      {
        if (!owned.is_element(global))
          return blocks.size();
        const auto local = owned.index_within_set(global);
        const auto it    = std::lower_bound(blocks.begin(),
                                         blocks.end(),
                                         local,
                                         [](const Block &b, const auto l)
                                         { return b.global < l; });
        Assert(it != blocks.end() && it->global == local,
               dealii::ExcInternalError());
        return it - blocks.begin();
      }
    } // namespace


    template <typename VectorType>
    void
    SeparableSet<VectorType>::set_disc_radius(const size_type k,
                                              const double    radius)
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      AssertThrow(k < added_discs.size(),
                  dealii::ExcMessage("set_disc_radius: disc " +
                                     std::to_string(k) + " of " +
                                     std::to_string(added_discs.size())));
      AssertThrow(radius >= 0. && std::isfinite(radius),
                  dealii::ExcMessage("disc radius must be >= 0 and finite, "
                                     "not " +
                                     std::to_string(radius)));
      added_discs[k].radius = radius;
      const std::size_t position =
        placed_position(discs, owned, added_discs[k].global);
      if (position < discs.size())
        discs[position].radius = radius;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::set_box_bounds(const size_type k,
                                             const double    lower,
                                             const double    upper)
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      AssertThrow(k < added_boxes.size(),
                  dealii::ExcMessage("set_box_bounds: box " +
                                     std::to_string(k) + " of " +
                                     std::to_string(added_boxes.size())));
      AssertThrow(lower <= upper,
                  dealii::ExcMessage("box bounds need lower <= upper, not " +
                                     std::to_string(lower) + " > " +
                                     std::to_string(upper)));
      added_boxes[k].lower = lower;
      added_boxes[k].upper = upper;
      const std::size_t position =
        placed_position(boxes, owned, added_boxes[k].global);
      if (position == boxes.size())
        return;
      boxes[position].lower = lower;
      boxes[position].upper = upper;
      // the SoA copies the box loops read
      box_lower[position] = lower;
      box_upper[position] = upper;
    }


    template <typename VectorType>
    bool
    SeparableSet<VectorType>::is_finalized() const
    {
      return finalized;
    }


    template <typename VectorType>
    double
    SeparableSet<VectorType>::active_tolerance() const
    {
      return tolerance;
    }


    template <typename VectorType>
    typename SeparableSet<VectorType>::size_type
    SeparableSet<VectorType>::n_blocks() const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      return std::accumulate(global_counts.begin(),
                             global_counts.end(),
                             size_type(0));
    }


    template <typename VectorType>
    typename SeparableSet<VectorType>::size_type
    SeparableSet<VectorType>::n_blocks(const BlockType type) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      return global_counts[static_cast<unsigned int>(type)];
    }


    template <typename VectorType>
    bool
    SeparableSet<VectorType>::only_bounds_and_boxes() const
    {
      return n_blocks(BlockType::disc) + n_blocks(BlockType::ellipse) +
               n_blocks(BlockType::cone) ==
             0;
    }

    // ======================== per-block kernels =========================
    // Each block kind gets the same small set of kernels; the set's public
    // operations are loops over the kinds calling them.  `Kernels` is a
    // local struct so that the tolerance is at hand.

    namespace
    {
      struct Kernels
      {
        double tol;

        // ---- bound ----
        inline bool
        bound_active(const double x, const double l) const
        {
          return x - l <= tol * std::abs(l);
        }
        // ---- box: -1 active at l, +1 active at u, 2 both (l = u), 0 free
        inline int
        box_state(const double x, const double l, const double u) const
        {
          const bool at_l = x - l <= tol * std::abs(l);
          const bool at_u = u - x <= tol * std::abs(u);
          if (at_l && at_u)
            return 2;
          return at_l ? -1 : (at_u ? 1 : 0);
        }
        // ---- disc ----
        inline bool
        disc_active(const double *x, const double r) const
        {
          return r - std::sqrt(x[0] * x[0] + x[1] * x[1]) <= tol * r;
        }
        // ---- ellipse ----
        inline bool
        ellipse_active(const EllipseFrame &e, const double *x) const
        {
          return 1. - e.enorm(x[0], x[1]) <= tol;
        }
        // ---- cone: 0 free, 1 on the smooth boundary, 2 apex
        inline int
        cone_state(const double mu, const double *x) const
        {
          const double rt = std::sqrt(x[1] * x[1] + x[2] * x[2]);
          if (x[0] <= 0.)
            return 2;
          const double norm = std::sqrt(x[0] * x[0] + rt * rt);
          return (mu * x[0] - rt <= tol * norm) ? 1 : 0;
        }

        // chopped gradient of an active cone block, written to beta
        inline void
        cone_chopped(const double  mu,
                     const double *x,
                     const double *g,
                     const int     state,
                     double       *beta) const
        {
          if (state == 2)
          {
            // apex: g^P = -P_K(-g), K the cone (= its own tangent cone)
            const double mg[3] = {-g[0], -g[1], -g[2]};
            double       z[3];
            project_cone(mu, mg, z);
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

        // does -g point into the set at an active cone block?  (the
        // "n'g > 0" test of the reduced chopped gradient)
        inline bool
        cone_inward(const double  mu,
                    const double *x,
                    const double *g,
                    const int     state) const
        {
          if (state == 2)
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
      };
    } // namespace


    // ======================== box runs ==================================

    namespace
    {
      // The smallest ratio room/q over q > 0 (the largest feasible step
      // of a bound or box along -q), tracked as a fraction compared by
      // cross-multiplication: no division per entry, no branch.  It works
      // on a lane of VectorKernels::RatioLanes (lane 0 for the boxes).
      struct MinRatio
      {
        double &num, &den;
        inline void
        offer(const double room, const double q)
        {
          const bool take = q > 0. && room * den < num * q;
          num             = take ? room : num;
          den             = take ? q : den;
        }
      };

      /**
       * A box block l_i <= x_i <= u_i in the loops over box runs (the
       * runs of bounds go to VectorKernels): at(first) views the run of
       * blocks starting at
       * the type's block `first`; classify() tests unknown i of the run at
       * the value y; chopped() is its component of beta for the gradient
       * component g; project() is P_i; offer_step() hands the largest step
       * along -p (p the direction component) to a MinRatio.
       */
      struct BoxKind
      {
        const double *lower, *upper;
        double        tol;
        struct State
        {
          bool at_lower, at_upper, active;
        };

        inline BoxKind
        at(const std::size_t first) const
        {
          return {lower + first, upper + first, tol};
        }
        inline State
        classify(const std::size_t i, const double y) const
        {
          const bool at_l = y - lower[i] <= tol * std::abs(lower[i]);
          const bool at_u = upper[i] - y <= tol * std::abs(upper[i]);
          return {at_l, at_u, at_l || at_u};
        }
        // l = u: both bounds active, beta = 0
        inline double
        chopped(const State &state, const double g) const
        {
          return (state.at_lower && state.at_upper) ?
                   0. :
                   (state.at_lower ? std::min(g, 0.) :
                                     (state.at_upper ? std::max(g, 0.) : 0.));
        }
        inline double
        project(const std::size_t i, const double y) const
        {
          return std::min(std::max(y, lower[i]), upper[i]);
        }
        inline void
        offer_step(const std::size_t i,
                   const double      y,
                   const double      p,
                   MinRatio         &ratio) const
        {
          const double room =
            p > 0. ? std::max(y - lower[i], 0.) : std::max(upper[i] - y, 0.);
          ratio.offer(room, std::abs(p));
        }
      };
    } // namespace


    // ======================== projection ================================

    template <typename VectorType>
    void
    SeparableSet<VectorType>::project(VectorType &x) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      double *v = x.begin();
      for (const Run &run : bound_runs)
      {
        double       *y = v + run.begin;
        const double *l = bound_lower.data() + run.first;
        for (std::size_t i = 0; i < run.count; ++i)
          y[i] = std::max(y[i], l[i]);
      }
      const BoxKind boxes{box_lower.data(), box_upper.data(), tolerance};
      for (const Run &run : box_runs)
      {
        double    *y = v + run.begin;
        const auto k = boxes.at(run.first);
        for (std::size_t i = 0; i < run.count; ++i)
          y[i] = k.project(i, y[i]);
      }
      project_curved(v);
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::project_curved(double *v) const
    {
      for (const auto &blk : discs)
      {
        double      *y = v + blk.global;
        const double n = std::sqrt(y[0] * y[0] + y[1] * y[1]);
        if (n > blk.radius)
        {
          const double s = blk.radius / n;
          y[0] *= s;
          y[1] *= s;
        }
      }
      for (const auto &blk : ellipses)
      {
        double            *y = v + blk.global;
        const EllipseFrame e{blk.a, blk.b, blk.cos_angle, blk.sin_angle};
        e.project(y[0], y[1], y[0], y[1]);
      }
      for (const auto &blk : cones)
      {
        double      *y    = v + blk.global;
        const double c[3] = {y[0], y[1], y[2]};
        project_cone(blk.mu, c, y);
      }
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::project(const VectorType &src,
                                      VectorType       &dst) const
    {
      dst = src;
      project(dst);
    }


    template <typename VectorType>
    double
    SeparableSet<VectorType>::feasibility_violation(const VectorType &x) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      const double *v   = x.begin();
      double        sum = 0.;
      for (const auto &blk : bounds)
        sum += sq(std::min(v[blk.global] - blk.lower, 0.));
      for (const auto &blk : boxes)
      {
        const double y = v[blk.global];
        sum += sq(y - std::min(std::max(y, blk.lower), blk.upper));
      }
      for (const auto &blk : discs)
      {
        const double *y = v + blk.global;
        const double  n = std::sqrt(y[0] * y[0] + y[1] * y[1]);
        sum += sq(std::max(n - blk.radius, 0.));
      }
      for (const auto &blk : ellipses)
      {
        const double      *y = v + blk.global;
        const EllipseFrame e{blk.a, blk.b, blk.cos_angle, blk.sin_angle};
        double             p1, p2;
        e.project(y[0], y[1], p1, p2);
        sum += sq(y[0] - p1) + sq(y[1] - p2);
      }
      for (const auto &blk : cones)
      {
        const double *y = v + blk.global;
        double        z[3];
        project_cone(blk.mu, y, z);
        sum += sq(y[0] - z[0]) + sq(y[1] - z[1]) + sq(y[2] - z[2]);
      }
      return std::sqrt(internal::sum(sum, x));
    }


    // ======================== steps =====================================

    template <typename VectorType>
    double
    SeparableSet<VectorType>::max_feasible_step(const VectorType &x,
                                                const VectorType &p) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      const double *v     = x.begin();
      const double *d     = p.begin();
      double        alpha = infinity;
      // bounds and boxes: branch-free, and without a division per entry:
      // the smallest ratio room/q over q > 0 is tracked as a fraction
      // (num, den) compared by cross-multiplication, in the lanes of
      // VectorKernels (boxes in lane 0)
      VectorKernels::RatioLanes ratio;
      for (const Run &run : bound_runs)
        VectorKernels::max_step(run.count,
                                v + run.begin,
                                d + run.begin,
                                bound_lower.data() + run.first,
                                ratio);
      {
        MinRatio      box_ratio{ratio.num[0], ratio.den[0]};
        const BoxKind boxes{box_lower.data(), box_upper.data(), tolerance};
        for (const Run &run : box_runs)
        {
          const double *y = v + run.begin;
          const double *q = d + run.begin;
          const auto    k = boxes.at(run.first);
          for (std::size_t i = 0; i < run.count; ++i)
            k.offer_step(i, y[i], q[i], box_ratio);
        }
      }
      alpha = VectorKernels::min_ratio(ratio);
      alpha = std::min(alpha, curved_max_step(v, d));
      return internal::min(alpha, x);
    }


    template <typename VectorType>
    bool
    SeparableSet<VectorType>::has_curved_blocks() const
    {
      return !discs.empty() || !ellipses.empty() || !cones.empty();
    }


    template <typename VectorType>
    double
    SeparableSet<VectorType>::curved_max_step(const double *v,
                                              const double *d) const
    {
      double alpha = infinity;
      for (const auto &blk : discs)
      {
        const double *y = v + blk.global;
        const double *q = d + blk.global;
        // ||y - alpha q||^2 <= r^2
        alpha = std::min(alpha,
                         positive_root(q[0] * q[0] + q[1] * q[1],
                                       y[0] * q[0] + y[1] * q[1],
                                       y[0] * y[0] + y[1] * y[1] -
                                         blk.radius * blk.radius));
      }
      for (const auto &blk : ellipses)
      {
        const double      *y = v + blk.global;
        const double      *q = d + blk.global;
        const EllipseFrame e{blk.a, blk.b, blk.cos_angle, blk.sin_angle};
        double             y1, y2, q1, q2;
        e.to_local(y[0], y[1], y1, y2);
        e.to_local(q[0], q[1], q1, q2);
        const double ia2 = 1. / (blk.a * blk.a), ib2 = 1. / (blk.b * blk.b);
        alpha = std::min(alpha,
                         positive_root(q1 * q1 * ia2 + q2 * q2 * ib2,
                                       y1 * q1 * ia2 + y2 * q2 * ib2,
                                       y1 * y1 * ia2 + y2 * y2 * ib2 - 1.));
      }
      for (const auto &blk : cones)
      {
        const double *y  = v + blk.global;
        const double *q  = d + blk.global;
        const double  mu = blk.mu;
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
          // concave quadratic: h <= 0 fails between its roots only
          // if they are positive; the feasible half of the double
          // cone ends at the larger... we need the first alpha > 0
          // where h changes from <= 0 to > 0.
          const double disc = B * B - A * std::min(C, 0.);
          if (disc > 0.)
          {
            const double s  = std::sqrt(disc);
            const double r1 = (B - s) / A, r2 = (B + s) / A;
            const double rl = std::min(r1, r2), rh = std::max(r1, r2);
            // h(a) = A a^2 - 2 B a + C > 0 between rl and rh
            if (rh > 0.)
              a_q = std::max(rl, 0.);
          }
        }
        else if (B < 0.) // linear: h(a) = -2 B a + C, increasing
          a_q = std::max(-C, 0.) / (-2. * B);
        alpha = std::min(alpha, std::min(a_lin, a_q));
      }
      return alpha;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::feasible_step(VectorType       &x,
                                            const VectorType &p,
                                            const double      alpha) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      Assert(alpha >= 0., dealii::ExcMessage("negative step"));
      double       *v = x.begin();
      const double *d = p.begin();
      // snap: the step length was computed in rounding arithmetic, so a
      // block that was meant to land on its bound may miss it by a few ulps
      // of the quantities involved
      const auto snap =
        [](const double y, const double bound, const double scale)
      { return std::abs(y - bound) <= 8. * epsilon * scale; };
      // one pass: x -= alpha p, bounds and boxes snapped on the way
      for (const auto &range : free_ranges)
        for (std::size_t i = range.first; i < range.second; ++i)
          v[i] -= alpha * d[i];
      for (const Run &run : bound_runs)
        VectorKernels::feasible_step(run.count,
                                     v + run.begin,
                                     d + run.begin,
                                     bound_lower.data() + run.first,
                                     alpha);
      for (const Run &run : box_runs)
      {
        double       *y = v + run.begin;
        const double *q = d + run.begin;
        const double *l = box_lower.data() + run.first;
        const double *u = box_upper.data() + run.first;
        for (std::size_t i = 0; i < run.count; ++i)
        {
          const double yi    = y[i] - alpha * q[i];
          const double scale = std::abs(yi) + std::abs(alpha * q[i]) +
                               std::abs(l[i]) + std::abs(u[i]);
          if (yi < l[i] || snap(yi, l[i], scale))
            y[i] = l[i];
          else if (yi > u[i] || snap(yi, u[i], scale))
            y[i] = u[i];
          else
            y[i] = yi;
        }
      }
      const auto step = [&](const size_type off, const unsigned int w)
      {
        for (unsigned int c = 0; c < w; ++c)
          v[off + c] -= alpha * d[off + c];
      };
      for (const auto &blk : discs)
        step(blk.global, 2);
      for (const auto &blk : ellipses)
        step(blk.global, 2);
      for (const auto &blk : cones)
        step(blk.global, 3);
      project_curved(v);
    }


    // ======================== gradients =================================

    // One sweep that computes, for each block, phi_j, beta_j (and the
    // reduced chopped part) and hands them to a sink.  All gradient
    // functions are thin wrappers, so the definitions live in one place.
    // sink(offset, width, phi[], beta[], red[]) with arrays of `width`.
    template <typename VectorType>
    template <typename Sink>
    void
    SeparableSet<VectorType>::sweep(const VectorType &x,
                                    const VectorType &g,
                                    const double      alpha,
                                    const bool        reduced,
                                    Sink             &sink,
                                    const bool        curved_only,
                                    const bool        skip_bounds) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      const Kernels            k{tolerance};
      const double            *v  = x.begin();
      const double            *gv = g.begin();
      const std::vector<Bound> no_bounds;
      const std::vector<Box>   no_boxes;
      double                   phi[3], beta[3], red[3];

      for (const auto &blk : (curved_only || skip_bounds ? no_bounds : bounds))
      {
        const double y = v[blk.global], gi = gv[blk.global];
        if (!k.bound_active(y, blk.lower))
        {
          phi[0]  = gi;
          beta[0] = red[0] = 0.;
        }
        else
        {
          phi[0]  = 0.;
          beta[0] = std::min(gi, 0.);
          if (reduced)
            red[0] =
              gi < 0. ? gi : (y - std::max(blk.lower, y - alpha * gi)) / alpha;
        }
        sink(blk.global, 1, phi, beta, red);
      }
      for (const auto &blk : (curved_only ? no_boxes : boxes))
      {
        const double y = v[blk.global], gi = gv[blk.global];
        const int    state = k.box_state(y, blk.lower, blk.upper);
        if (state == 0)
        {
          phi[0]  = gi;
          beta[0] = red[0] = 0.;
        }
        else
        {
          phi[0] = 0.;
          bool inward;
          if (state == -1)
          {
            beta[0] = std::min(gi, 0.);
            inward  = gi < 0.;
          }
          else if (state == 1)
          {
            beta[0] = std::max(gi, 0.);
            inward  = gi > 0.;
          }
          else
          {
            beta[0] = 0.;
            inward  = false;
          }
          if (reduced)
            red[0] =
              inward ?
                gi :
                (y - std::min(std::max(y - alpha * gi, blk.lower), blk.upper)) /
                  alpha;
        }
        sink(blk.global, 1, phi, beta, red);
      }
      for (const auto &blk : discs)
      {
        const double *y = v + blk.global, *gj = gv + blk.global;
        if (!k.disc_active(y, blk.radius))
        {
          phi[0]  = gj[0];
          phi[1]  = gj[1];
          beta[0] = beta[1] = red[0] = red[1] = 0.;
        }
        else
        {
          phi[0] = phi[1] = 0.;
          const double n  = std::sqrt(y[0] * y[0] + y[1] * y[1]);
          bool         inward;
          if (n == 0.) // radius 0: the set is a point
          {
            beta[0] = beta[1] = 0.;
            inward            = false;
          }
          else
          {
            const double n0 = y[0] / n, n1 = y[1] / n;
            const double ng = n0 * gj[0] + n1 * gj[1];
            const double c  = std::min(ng, 0.);
            beta[0]         = gj[0] - c * n0;
            beta[1]         = gj[1] - c * n1;
            inward          = ng > 0.;
          }
          if (reduced)
          {
            if (inward)
            {
              red[0] = gj[0];
              red[1] = gj[1];
            }
            else
            {
              double       z0 = y[0] - alpha * gj[0];
              double       z1 = y[1] - alpha * gj[1];
              const double m  = std::sqrt(z0 * z0 + z1 * z1);
              if (m > blk.radius)
              {
                z0 *= blk.radius / m;
                z1 *= blk.radius / m;
              }
              red[0] = (y[0] - z0) / alpha;
              red[1] = (y[1] - z1) / alpha;
            }
          }
        }
        sink(blk.global, 2, phi, beta, red);
      }
      for (const auto &blk : ellipses)
      {
        const double      *y = v + blk.global, *gj = gv + blk.global;
        const EllipseFrame e{blk.a, blk.b, blk.cos_angle, blk.sin_angle};
        if (!k.ellipse_active(e, y))
        {
          phi[0]  = gj[0];
          phi[1]  = gj[1];
          beta[0] = beta[1] = red[0] = red[1] = 0.;
        }
        else
        {
          phi[0] = phi[1] = 0.;
          double n0, n1;
          e.normal(y[0], y[1], n0, n1);
          const double ng = n0 * gj[0] + n1 * gj[1];
          const double c  = std::min(ng, 0.);
          beta[0]         = gj[0] - c * n0;
          beta[1]         = gj[1] - c * n1;
          if (reduced)
          {
            if (ng > 0.)
            {
              red[0] = gj[0];
              red[1] = gj[1];
            }
            else
            {
              double z0, z1;
              e.project(y[0] - alpha * gj[0], y[1] - alpha * gj[1], z0, z1);
              red[0] = (y[0] - z0) / alpha;
              red[1] = (y[1] - z1) / alpha;
            }
          }
        }
        sink(blk.global, 2, phi, beta, red);
      }
      for (const auto &blk : cones)
      {
        const double *y = v + blk.global, *gj = gv + blk.global;
        const int     state = k.cone_state(blk.mu, y);
        if (state == 0)
        {
          phi[0]  = gj[0];
          phi[1]  = gj[1];
          phi[2]  = gj[2];
          beta[0] = beta[1] = beta[2] = red[0] = red[1] = red[2] = 0.;
        }
        else
        {
          phi[0] = phi[1] = phi[2] = 0.;
          k.cone_chopped(blk.mu, y, gj, state, beta);
          if (reduced)
          {
            if (k.cone_inward(blk.mu, y, gj, state))
            {
              red[0] = gj[0];
              red[1] = gj[1];
              red[2] = gj[2];
            }
            else
            {
              const double w[3] = {y[0] - alpha * gj[0],
                                   y[1] - alpha * gj[1],
                                   y[2] - alpha * gj[2]};
              double       z[3];
              project_cone(blk.mu, w, z);
              for (unsigned int c = 0; c < 3; ++c)
                red[c] = (y[c] - z[c]) / alpha;
            }
          }
        }
        sink(blk.global, 3, phi, beta, red);
      }
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::split_gradient(const VectorType &x,
                                             const VectorType &g,
                                             VectorType       &phi_out,
                                             VectorType       &beta_out) const
    {
      // unconstrained unknowns: phi = g, beta = 0
      phi_out    = g;
      beta_out   = 0.;
      double *pf = phi_out.begin(), *pb = beta_out.begin();
      auto    sink = [pf, pb](const size_type o,
                           const unsigned  w,
                           const double   *phi,
                           const double   *beta,
                           const double *)
      {
        for (unsigned c = 0; c < w; ++c)
        {
          pf[o + c] = phi[c];
          pb[o + c] = beta[c];
        }
      };
      sweep(x, g, 1., false, sink);
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::free_gradient(const VectorType &x,
                                            const VectorType &g,
                                            VectorType       &out) const
    {
      out             = g;
      double       *o = out.begin();
      const double *v = x.begin();
      for (const Run &run : bound_runs)
      {
        const double *y = v + run.begin;
        double       *f = o + run.begin;
        const double *l = bound_lower.data() + run.first;
        for (std::size_t i = 0; i < run.count; ++i)
          f[i] = (y[i] - l[i] <= tolerance * std::abs(l[i])) ? 0. : f[i];
      }
      for (const Run &run : box_runs)
      {
        const double *y = v + run.begin;
        double       *f = o + run.begin;
        const double *l = box_lower.data() + run.first;
        const double *u = box_upper.data() + run.first;
        for (std::size_t i = 0; i < run.count; ++i)
          f[i] = (y[i] - l[i] <= tolerance * std::abs(l[i]) ||
                  u[i] - y[i] <= tolerance * std::abs(u[i])) ?
                   0. :
                   f[i];
      }
      auto sink = [o](const size_type o_,
                      const unsigned  w,
                      const double   *phi,
                      const double *,
                      const double *)
      {
        for (unsigned c = 0; c < w; ++c)
          o[o_ + c] = phi[c];
      };
      sweep(x, g, 1., false, sink, true);
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::chopped_gradient(const VectorType &x,
                                               const VectorType &g,
                                               VectorType       &out) const
    {
      out          = 0.;
      double *o    = out.begin();
      auto    sink = [o](const size_type o_,
                      const unsigned  w,
                      const double *,
                      const double *beta,
                      const double *)
      {
        for (unsigned c = 0; c < w; ++c)
          o[o_ + c] = beta[c];
      };
      sweep(x, g, 1., false, sink);
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::projected_gradient(const VectorType &x,
                                                 const VectorType &g,
                                                 VectorType       &out) const
    {
      out          = g;
      double *o    = out.begin();
      auto    sink = [o](const size_type o_,
                      const unsigned  w,
                      const double   *phi,
                      const double   *beta,
                      const double *)
      {
        for (unsigned c = 0; c < w; ++c)
          o[o_ + c] = phi[c] + beta[c];
      };
      sweep(x, g, 1., false, sink);
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::reduced_gradient(const VectorType &x,
                                               const VectorType &g,
                                               const double      alpha,
                                               VectorType       &out) const
    {
      AssertThrow(alpha > 0.,
                  dealii::ExcMessage("reduced gradient: alpha must be > 0"));
      // (x - P(x - alpha g)) / alpha; free unknowns give g exactly
      out.equ(1., x);
      out.add(-alpha, g);
      project(out);
      out.sadd(-1. / alpha, 1. / alpha, x);
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::reduced_projected_gradient(const VectorType &x,
                                                         const VectorType &g,
                                                         const double alpha,
                                                         VectorType  &out) const
    {
      AssertThrow(alpha > 0.,
                  dealii::ExcMessage(
                    "reduced projected gradient: alpha must be > 0"));
      out          = g;
      double *o    = out.begin();
      auto    sink = [o](const size_type o_,
                      const unsigned  w,
                      const double   *phi,
                      const double *,
                      const double *red)
      {
        for (unsigned c = 0; c < w; ++c)
          o[o_ + c] = phi[c] + red[c];
      };
      sweep(x, g, alpha, true, sink);
    }


    template <typename VectorType>
    GradientNorms
    SeparableSet<VectorType>::gradient_norms(const VectorType &x,
                                             const VectorType &g) const
    {
      return norms(x, g, 1., false);
    }


    template <typename VectorType>
    GradientNorms
    SeparableSet<VectorType>::free_gradient_and_norms(const VectorType &x,
                                                      const VectorType &g,
                                                      VectorType &phi) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      Assert(&phi != &g, dealii::ExcMessage("phi must not alias g"));
      return norms(x, g, 1., false, phi.begin());
    }


    // ======================== fused passes ==============================

    template <typename VectorType>
    GradientNorms
    SeparableSet<VectorType>::cg_step(VectorType       &x,
                                      VectorType       &g,
                                      const VectorType &p,
                                      const VectorType &Ap,
                                      const double      alpha,
                                      double           &phi_dot_Ap,
                                      const double      reduced_alpha) const
    {
      const bool reduced = reduced_alpha > 0.;
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      double       *v  = x.begin();
      double       *gv = g.begin();
      const double *pv = p.begin();
      const double *av = Ap.begin();
      // eight lanes (VectorKernels): the runs of bounds in the vectorized
      // kernel, everything else in lane 0
      VectorKernels::Lanes fs, bs, pa_lanes, rs;
      double              &fsq = fs.v[0], &bsq = bs.v[0], &pa = pa_lanes.v[0],
             &rsq = rs.v[0];
      for (const auto &range : free_ranges)
        for (std::size_t i = range.first; i < range.second; ++i)
        {
          v[i] -= alpha * pv[i];
          gv[i] -= alpha * av[i];
          fsq += gv[i] * gv[i];
          pa += gv[i] * av[i];
        }
      for (const Run &run : bound_runs)
        if (reduced)
          VectorKernels::cg_step_reduced(run.count,
                                         v + run.begin,
                                         gv + run.begin,
                                         pv + run.begin,
                                         av + run.begin,
                                         bound_lower.data() + run.first,
                                         tolerance,
                                         alpha,
                                         reduced_alpha,
                                         fs,
                                         bs,
                                         pa_lanes,
                                         rs);
        else
          VectorKernels::cg_step(run.count,
                                 v + run.begin,
                                 gv + run.begin,
                                 pv + run.begin,
                                 av + run.begin,
                                 bound_lower.data() + run.first,
                                 tolerance,
                                 alpha,
                                 fs,
                                 bs,
                                 pa_lanes);
      const BoxKind boxes{box_lower.data(), box_upper.data(), tolerance};
      for (const Run &run : box_runs)
      {
        double       *y = v + run.begin;
        double       *q = gv + run.begin;
        const double *d = pv + run.begin;
        const double *a = av + run.begin;
        const auto    k = boxes.at(run.first);
        for (std::size_t i = 0; i < run.count; ++i)
        {
          y[i] -= alpha * d[i];
          q[i] -= alpha * a[i];
          const auto   state = k.classify(i, y[i]);
          const double c     = k.chopped(state, q[i]);
          fsq += state.active ? 0. : q[i] * q[i];
          bsq += c * c;
          pa += state.active ? 0. : q[i] * a[i];
          if (reduced && state.active)
          {
            // the sweep's reduced component of a box: the gradient if it
            // points into the box, else the projected step's length
            const bool inward = !(state.at_lower && state.at_upper) &&
                                (state.at_lower ? q[i] < 0. : q[i] > 0.);
            const double red =
              inward ? q[i] :
                       (y[i] - k.project(i, y[i] - reduced_alpha * q[i])) /
                         reduced_alpha;
            rsq += red * red;
          }
        }
      }
      if (has_curved_blocks())
      {
        const auto step = [&](const size_type off, const unsigned int w)
        {
          for (unsigned int c = 0; c < w; ++c)
          {
            v[off + c] -= alpha * pv[off + c];
            gv[off + c] -= alpha * av[off + c];
          }
        };
        for (const auto &blk : discs)
          step(blk.global, 2);
        for (const auto &blk : ellipses)
          step(blk.global, 2);
        for (const auto &blk : cones)
          step(blk.global, 3);
        auto sink = [&](const size_type off,
                        const unsigned  w,
                        const double   *fphi,
                        const double   *beta,
                        const double   *red)
        {
          for (unsigned c = 0; c < w; ++c)
          {
            fsq += fphi[c] * fphi[c];
            bsq += beta[c] * beta[c];
            pa += fphi[c] * av[off + c];
            if (reduced)
              rsq += red[c] * red[c];
          }
        };
        sweep(x, g, reduced ? reduced_alpha : 1., reduced, sink, true);
      }
      double local[4] = {fs.total(), bs.total(), pa_lanes.total(), rs.total()},
             global[4];
      dealii::Utilities::MPI::sum(dealii::ArrayView<const double>(local, 4),
                                  internal::communicator(x),
                                  dealii::ArrayView<double>(global, 4));
      GradientNorms n;
      n.free_sq            = global[0];
      n.chopped_sq         = global[1];
      n.reduced_chopped_sq = global[3];
      phi_dot_Ap           = global[2];
      return n;
    }


    template <typename VectorType>
    typename SeparableSet<VectorType>::Direction
    SeparableSet<VectorType>::conjugate_direction(const VectorType &x,
                                                  const VectorType &g,
                                                  const double      beta,
                                                  VectorType       &p) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      const double *v  = x.begin();
      const double *gv = g.begin();
      double       *pv = p.begin();
      // eight lanes (VectorKernels): the runs of bounds in the vectorized
      // kernel, everything else in lane 0
      VectorKernels::Lanes      pp_lanes, gp_lanes;
      VectorKernels::RatioLanes ratio;
      double                   &pp0 = pp_lanes.v[0], &gp0 = gp_lanes.v[0];
      for (const auto &range : free_ranges)
        for (std::size_t i = range.first; i < range.second; ++i)
        {
          pv[i] = gv[i] - beta * pv[i];
          pp0 += pv[i] * pv[i];
          gp0 += gv[i] * pv[i];
        }
      for (const Run &run : bound_runs)
        VectorKernels::conjugate_direction(run.count,
                                           v + run.begin,
                                           gv + run.begin,
                                           bound_lower.data() + run.first,
                                           tolerance,
                                           beta,
                                           pv + run.begin,
                                           pp_lanes,
                                           gp_lanes,
                                           ratio);
      {
        MinRatio      box_ratio{ratio.num[0], ratio.den[0]};
        const BoxKind boxes{box_lower.data(), box_upper.data(), tolerance};
        for (const Run &run : box_runs)
        {
          const double *y = v + run.begin;
          const double *q = gv + run.begin;
          double       *d = pv + run.begin;
          const auto    k = boxes.at(run.first);
          for (std::size_t i = 0; i < run.count; ++i)
          {
            const auto   state = k.classify(i, y[i]);
            const double di    = (state.active ? 0. : q[i]) - beta * d[i];
            d[i]               = di;
            pp0 += di * di;
            gp0 += q[i] * di;
            k.offer_step(i, y[i], di, box_ratio);
          }
        }
      }
      double alpha = VectorKernels::min_ratio(ratio);
      double pp    = pp_lanes.total();
      double gp    = gp_lanes.total();
      if (has_curved_blocks())
      {
        auto sink = [&](const size_type off,
                        const unsigned  w,
                        const double   *fphi,
                        const double *,
                        const double *)
        {
          for (unsigned c = 0; c < w; ++c)
          {
            double &di = pv[off + c];
            di         = fphi[c] - beta * di;
            pp += di * di;
            gp += gv[off + c] * di;
          }
        };
        sweep(x, g, 1., false, sink, true);
        alpha = std::min(alpha, curved_max_step(v, pv));
      }
      double local[2] = {pp, gp}, global[2];
      dealii::Utilities::MPI::sum(dealii::ArrayView<const double>(local, 2),
                                  internal::communicator(x),
                                  dealii::ArrayView<double>(global, 2));
      Direction result;
      result.max_step = internal::min(alpha, x);
      result.pp       = global[0];
      result.gp       = global[1];
      return result;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::projected_step(VectorType       &x,
                                             const VectorType &g,
                                             const double      alpha,
                                             const bool        free_only) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      Assert(&x != &g, dealii::ExcMessage("g must not be x"));
      double       *v  = x.begin();
      const double *gv = g.begin();
      for (const auto &range : free_ranges)
        for (std::size_t i = range.first; i < range.second; ++i)
          v[i] -= alpha * gv[i];
      for (const Run &run : bound_runs)
        VectorKernels::projected_step(run.count,
                                      v + run.begin,
                                      gv + run.begin,
                                      bound_lower.data() + run.first,
                                      tolerance,
                                      alpha,
                                      free_only);
      const BoxKind boxes{box_lower.data(), box_upper.data(), tolerance};
      for (const Run &run : box_runs)
      {
        double       *y = v + run.begin;
        const double *q = gv + run.begin;
        const auto    k = boxes.at(run.first);
        for (std::size_t i = 0; i < run.count; ++i)
        {
          const bool active = free_only && k.classify(i, y[i]).active;
          y[i]              = k.project(i, y[i] - alpha * (active ? 0. : q[i]));
        }
      }
      if (has_curved_blocks())
      {
        // the step along phi (free_only) or g on every curved block, then
        // their projections; the sink runs after the sweep has read the
        // block it is given, so it may move that block
        auto sink = [&](const size_type off,
                        const unsigned  w,
                        const double   *fphi,
                        const double *,
                        const double *)
        {
          for (unsigned c = 0; c < w; ++c)
            v[off + c] -= alpha * (free_only ? fphi[c] : gv[off + c]);
        };
        sweep(x, g, 1., false, sink, true);
        project_curved(v);
      }
    }


    template <typename VectorType>
    GradientNorms
    SeparableSet<VectorType>::reduced_gradient_norms(const VectorType &x,
                                                     const VectorType &g,
                                                     const double alpha) const
    {
      AssertThrow(alpha > 0.,
                  dealii::ExcMessage("reduced gradient: alpha must be > 0"));
      return norms(x, g, alpha, true);
    }


    template <typename VectorType>
    GradientNorms
    SeparableSet<VectorType>::norms(const VectorType &x,
                                    const VectorType &g,
                                    const double      alpha,
                                    const bool        reduced,
                                    double           *phi) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      Assert(!reduced || phi == nullptr, dealii::ExcInternalError());
      const double *gv  = g.begin();
      const double *v   = x.begin();
      double        fsq = 0., bsq = 0., rsq = 0.;
      for (const auto &range : free_ranges)
        for (std::size_t i = range.first; i < range.second; ++i)
        {
          if (phi != nullptr)
            phi[i] = gv[i];
          fsq += gv[i] * gv[i];
        }
      auto sink = [&](const size_type off,
                      const unsigned  w,
                      const double   *fphi,
                      const double   *beta,
                      const double   *red)
      {
        for (unsigned c = 0; c < w; ++c)
        {
          if (phi != nullptr)
            phi[off + c] = fphi[c];
          fsq += fphi[c] * fphi[c];
          bsq += beta[c] * beta[c];
          if (reduced)
            rsq += red[c] * red[c];
        }
      };
      VectorKernels::Lanes fs_lanes, bs_lanes, rs_lanes;
      if (reduced)
      {
        // bounds in the vectorized kernel, boxes and curved blocks in the
        // sweep
        for (const Run &run : bound_runs)
          VectorKernels::reduced_norms(run.count,
                                       v + run.begin,
                                       gv + run.begin,
                                       bound_lower.data() + run.first,
                                       tolerance,
                                       alpha,
                                       fs_lanes,
                                       bs_lanes,
                                       rs_lanes);
        fsq += fs_lanes.total();
        bsq += bs_lanes.total();
        rsq += rs_lanes.total();
        sweep(x, g, alpha, true, sink, false, true);
      }
      else
      {
        // bounds in the vectorized kernel, boxes in a branch-free loop,
        // curved blocks in the sweep
        for (const Run &run : bound_runs)
          VectorKernels::gradient_norms(run.count,
                                        v + run.begin,
                                        gv + run.begin,
                                        bound_lower.data() + run.first,
                                        tolerance,
                                        phi == nullptr ? nullptr :
                                                         phi + run.begin,
                                        fs_lanes,
                                        bs_lanes);
        fsq += fs_lanes.total();
        bsq += bs_lanes.total();
        const BoxKind boxes{box_lower.data(), box_upper.data(), tolerance};
        for (const Run &run : box_runs)
        {
          const double *y = v + run.begin;
          const double *q = gv + run.begin;
          const auto    k = boxes.at(run.first);
          double        f = 0., b = 0.;
          for (std::size_t i = 0; i < run.count; ++i)
          {
            const auto   state = k.classify(i, y[i]);
            const double c     = k.chopped(state, q[i]);
            if (phi != nullptr)
              phi[run.begin + i] = state.active ? 0. : q[i];
            f += state.active ? 0. : q[i] * q[i];
            b += c * c;
          }
          fsq += f;
          bsq += b;
        }
        sweep(x, g, 1., false, sink, true);
      }
      double local[3] = {fsq, bsq, rsq};
      double global[3];
      dealii::Utilities::MPI::sum(dealii::ArrayView<const double>(local, 3),
                                  internal::communicator(x),
                                  dealii::ArrayView<double>(global, 3));
      GradientNorms n;
      n.free_sq            = global[0];
      n.chopped_sq         = global[1];
      n.reduced_chopped_sq = global[2];
      return n;
    }


    template <typename VectorType>
    double
    SeparableSet<VectorType>::reduced_gradient_norm(const VectorType &x,
                                                    const VectorType &g,
                                                    const double alpha) const
    {
      AssertThrow(alpha > 0.,
                  dealii::ExcMessage("reduced gradient: alpha must be > 0"));
      // free unknowns contribute g exactly; blocks (x_j - P_j(x_j -
      // alpha g_j)) / alpha
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      const double *v    = x.begin();
      const double *gv   = g.begin();
      double        free = 0., blocks = 0.;
      for (const auto &range : free_ranges)
        for (std::size_t i = range.first; i < range.second; ++i)
          free += gv[i] * gv[i];
      for (const Run &run : bound_runs)
      {
        const double *y = v + run.begin;
        const double *q = gv + run.begin;
        const double *l = bound_lower.data() + run.first;
        double        b = 0.;
        for (std::size_t i = 0; i < run.count; ++i)
          b += sq(y[i] - std::max(y[i] - alpha * q[i], l[i]));
        blocks += b / (alpha * alpha);
      }
      for (const Run &run : box_runs)
      {
        const double *y = v + run.begin;
        const double *q = gv + run.begin;
        const double *l = box_lower.data() + run.first;
        const double *u = box_upper.data() + run.first;
        double        b = 0.;
        for (std::size_t i = 0; i < run.count; ++i)
          b += sq(y[i] - std::min(std::max(y[i] - alpha * q[i], l[i]), u[i]));
        blocks += b / (alpha * alpha);
      }
      for (const auto &blk : discs)
      {
        const double *y = v + blk.global, *gj = gv + blk.global;
        double        z0 = y[0] - alpha * gj[0], z1 = y[1] - alpha * gj[1];
        const double  m = std::sqrt(z0 * z0 + z1 * z1);
        if (m > blk.radius)
        {
          z0 *= blk.radius / m;
          z1 *= blk.radius / m;
        }
        blocks += (sq(y[0] - z0) + sq(y[1] - z1)) / (alpha * alpha);
      }
      for (const auto &blk : ellipses)
      {
        const double      *y = v + blk.global, *gj = gv + blk.global;
        const EllipseFrame e{blk.a, blk.b, blk.cos_angle, blk.sin_angle};
        double             z0, z1;
        e.project(y[0] - alpha * gj[0], y[1] - alpha * gj[1], z0, z1);
        blocks += (sq(y[0] - z0) + sq(y[1] - z1)) / (alpha * alpha);
      }
      for (const auto &blk : cones)
      {
        const double *y = v + blk.global, *gj = gv + blk.global;
        const double  w[3] = {y[0] - alpha * gj[0],
                              y[1] - alpha * gj[1],
                              y[2] - alpha * gj[2]};
        double        z[3];
        project_cone(blk.mu, w, z);
        blocks += (sq(y[0] - z[0]) + sq(y[1] - z[1]) + sq(y[2] - z[2])) /
                  (alpha * alpha);
      }
      return std::sqrt(internal::sum(free + blocks, x));
    }


    // ======================== active set ================================

    template <typename VectorType>
    void
    SeparableSet<VectorType>::zero_active(const VectorType &x,
                                          VectorType       &v) const
    {
      // phi of v (taken as a "gradient") is v on free blocks and 0 on
      // active ones; the sweep reads a block before the sink writes it
      double *o    = v.begin();
      auto    sink = [o](const size_type off,
                      const unsigned  w,
                      const double   *phi,
                      const double *,
                      const double *)
      {
        for (unsigned c = 0; c < w; ++c)
          o[off + c] = phi[c];
      };
      const VectorType &view = v;
      sweep(x, view, 1., false, sink);
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::active_mask(const VectorType &x,
                                          VectorType       &mask) const
    {
      mask = 1.;
      zero_active(x, mask); // 1 on free entries, 0 on active ones
      double *m = mask.begin();
      for (std::size_t i = 0; i < local_size; ++i)
        m[i] = 1. - m[i];
    }


    template <typename VectorType>
    std::array<typename SeparableSet<VectorType>::size_type, n_block_types>
    SeparableSet<VectorType>::n_active_blocks(const VectorType &x) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      const Kernels k{tolerance};
      const double *v                    = x.begin();
      double        local[n_block_types] = {0., 0., 0., 0., 0.};
      for (const auto &blk : bounds)
        local[0] += k.bound_active(v[blk.global], blk.lower) ? 1 : 0;
      for (const auto &blk : boxes)
        local[1] += k.box_state(v[blk.global], blk.lower, blk.upper) ? 1 : 0;
      for (const auto &blk : discs)
        local[2] += k.disc_active(v + blk.global, blk.radius) ? 1 : 0;
      for (const auto &blk : ellipses)
        local[3] += k.ellipse_active(
                      EllipseFrame{blk.a, blk.b, blk.cos_angle, blk.sin_angle},
                      v + blk.global) ?
                      1 :
                      0;
      for (const auto &blk : cones)
        local[4] += k.cone_state(blk.mu, v + blk.global) ? 1 : 0;
      double global[n_block_types];
      dealii::Utilities::MPI::sum(
        dealii::ArrayView<const double>(local, n_block_types),
        internal::communicator(x),
        dealii::ArrayView<double>(global, n_block_types));
      std::array<size_type, n_block_types> result;
      for (unsigned int t = 0; t < n_block_types; ++t)
        result[t] = static_cast<size_type>(global[t] + 0.5);
      return result;
    }


    template <typename VectorType>
    bool
    SeparableSet<VectorType>::is_active(const VectorType &x,
                                        const size_type   first) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      AssertThrow(owned.is_element(first),
                  dealii::ExcMessage("is_active: unknown " +
                                     std::to_string(first) +
                                     " is not locally owned"));
      const size_type off = owned.index_within_set(first);
      const Kernels   k{tolerance};
      const double   *v = x.begin();
      for (const auto &blk : bounds)
        if (blk.global == off)
          return k.bound_active(v[off], blk.lower);
      for (const auto &blk : boxes)
        if (blk.global == off)
          return k.box_state(v[off], blk.lower, blk.upper) != 0;
      for (const auto &blk : discs)
        if (blk.global == off)
          return k.disc_active(v + off, blk.radius);
      for (const auto &blk : ellipses)
        if (blk.global == off)
          return k.ellipse_active(
            EllipseFrame{blk.a, blk.b, blk.cos_angle, blk.sin_angle}, v + off);
      for (const auto &blk : cones)
        if (blk.global == off)
          return k.cone_state(blk.mu, v + off) != 0;
      AssertThrow(false,
                  dealii::ExcMessage("is_active: no block starts at unknown " +
                                     std::to_string(first)));
      return false;
    }


    template <typename VectorType>
    double
    SeparableSet<VectorType>::complementarity(const VectorType &x,
                                              const VectorType &g) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      const double *v   = x.begin();
      const double *gv  = g.begin();
      double        sum = 0.;
      for (const auto &blk : bounds)
        // multiplier g_i (outward normal -1), distance x_i - l
        sum +=
          std::max(gv[blk.global], 0.) * std::abs(v[blk.global] - blk.lower);
      for (const auto &blk : boxes)
      {
        const double y = v[blk.global], gi = gv[blk.global];
        if (y - blk.lower <= blk.upper - y)
          sum += std::max(gi, 0.) * std::abs(y - blk.lower);
        else
          sum += std::max(-gi, 0.) * std::abs(blk.upper - y);
      }
      for (const auto &blk : discs)
      {
        const double *y = v + blk.global, *gj = gv + blk.global;
        const double  n = std::sqrt(y[0] * y[0] + y[1] * y[1]);
        if (n > 0.)
          sum += std::max(-(y[0] * gj[0] + y[1] * gj[1]) / n, 0.) *
                 std::abs(blk.radius - n);
      }
      for (const auto &blk : ellipses)
      {
        // nearest boundary point approximated by the radial one x/q
        const double      *y = v + blk.global, *gj = gv + blk.global;
        const EllipseFrame e{blk.a, blk.b, blk.cos_angle, blk.sin_angle};
        const double       q = e.enorm(y[0], y[1]);
        if (q > 0.)
        {
          double n0, n1;
          e.normal(y[0] / q, y[1] / q, n0, n1);
          const double dist =
            std::abs(1. - 1. / q) * std::sqrt(y[0] * y[0] + y[1] * y[1]);
          sum += std::max(-(n0 * gj[0] + n1 * gj[1]), 0.) * dist;
        }
      }
      for (const auto &blk : cones)
      {
        const double *y = v + blk.global, *gj = gv + blk.global;
        const double  rt  = std::sqrt(y[1] * y[1] + y[2] * y[2]);
        const double  inv = 1. / std::sqrt(1. + blk.mu * blk.mu);
        if (rt > 0.)
        {
          const double ng =
            (-blk.mu * gj[0] + (y[1] * gj[1] + y[2] * gj[2]) / rt) * inv;
          sum += std::max(-ng, 0.) * std::abs(blk.mu * y[0] - rt) * inv;
        }
        else if (y[0] > 0.)
        {
          // on the axis: the worst normal is the one against g_t
          const double gt = std::sqrt(gj[1] * gj[1] + gj[2] * gj[2]);
          const double ng = (-blk.mu * gj[0] - gt) * inv;
          sum += std::max(-ng, 0.) * blk.mu * y[0] * inv;
        }
      }
      return internal::sum(sum, x);
    }


    template class SeparableSet<dealii::Vector<double>>;
    template class SeparableSet<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
