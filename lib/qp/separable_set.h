/**
 * @file separable_set.h
 * The feasible set Omega = Omega_1 x ... x Omega_m of the QP, a product of
 * small blocks (thesis 1.4.1, 1.6).  Everything an active-set or projection
 * solver needs from the constraints lives here, so that the solvers never
 * look at a block's type.
 */
#ifndef dualcontact_qp_separable_set_h
#define dualcontact_qp_separable_set_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/types.h>

#include <qp/block_type.h>
#include <qp/blocks/bound.h>
#include <qp/blocks/box.h>
#include <qp/blocks/cone.h>
#include <qp/blocks/disc.h>
#include <qp/blocks/ellipse.h>

#include <array>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

namespace dualcontact
{
  namespace qp
  {
    /**
     * Squared norms of the pieces of the gradient, computed in one sweep
     * without forming any vector (what a solver needs every iteration).
     */
    struct GradientNorms
    {
      /// ||phi||^2: free gradient (g on free blocks and free unknowns)
      double free_sq = 0.;
      /// ||beta||^2: chopped gradient (thesis 1.31)
      double chopped_sq = 0.;
      /// ||beta~_alpha||^2: reduced chopped gradient (thesis 1.4.3);
      /// only filled by reduced_gradient_norms() and cg_step() with a
      /// reduced alpha
      double reduced_chopped_sq = 0.;
    };

    /**
     * A separable convex set, the product of blocks of the BlockType kinds
     * (one type each in qp/blocks/, which hold each kind's arithmetic);
     * unknowns in no block are free (unconstrained).
     *
     * Building: call the add_*() functions with GLOBAL indices (every rank
     * may add all blocks, or only those it owns; blocks that are not locally
     * owned are dropped), then finalize() with a vector of the layout the
     * solver will use.  A block must lie entirely on one rank (checked).
     * After finalize() the set only works on vectors of that layout, and
     * only on the locally owned entries; scalars (norms, steps, counts) are
     * reduced over the vector's communicator, so every rank gets the same.
     *
     * Active set (thesis 1.30): a block is active when x lies on its
     * boundary up to the relative tolerance `tol` given to the constructor,
     * tests that do not depend on the scale of x:
     * bound/box: x_i - l <= tol |l| (exactly x_i = l when l = 0), likewise
     * at u, and l = u is always active; disc: r - ||x|| <= tol r; ellipse:
     * 1 - ||x||_E <= tol (||.||_E the norm whose unit ball is the
     * ellipse); cone: mu x_f - ||x_t|| <= tol ||x||, the apex when x_f <= 0.
     * Points produced by project() and feasible_step() pass these tests.
     *
     * Gradients (thesis 1.4), for g = Ax - b at a feasible x, n_j the unit
     * outward normal of an active block (box: -1 at l, +1 at u):
     *  - free phi:    g on free blocks / free unknowns, 0 on active blocks;
     *  - chopped beta: 0 on free blocks, g_j - min(n_j'g_j, 0) n_j on active
     *    blocks, i.e. -g_j with its outward part removed; at a cone apex
     *    (where the normal is not unique) the exact generalisation
     *    -P_{T}(-g_j), T the tangent cone (= the cone itself); a box with
     *    l = u is always active and has beta = 0;
     *  - projected g^P = phi + beta, zero exactly at the solution;
     *  - reduced g~_alpha = (x - P(x - alpha g)) / alpha (thesis 1.33);
     *  - reduced projected g~^P_alpha = phi + beta~_alpha, with beta~_alpha_j
     *    = g_j on active blocks where n_j'g_j > 0 (the solver would move
     *    inwards) and (x_j - P_j(x_j - alpha g_j))/alpha where n_j'g_j <= 0.
     *
     * Steps: solvers move as x - alpha p (p a gradient-like direction), so
     * max_feasible_step(x, p) is the largest alpha >= 0 with x - alpha p in
     * Omega (thesis 2.4, CG half-step), +infinity if there is none.
     */
    template <typename VectorType>
    class SeparableSet
    {
    public:
      using size_type = dealii::types::global_dof_index;

      /// @p active_tolerance: relative tolerance of the active-set test.
      explicit SeparableSet(const double active_tolerance = 1e-12);

      /// x_first >= lower.
      void
      add_bound(size_type first, double lower);
      /// lower <= x_first <= upper (lower <= upper; lower = upper allowed).
      void
      add_box(size_type first, double lower, double upper);
      /// ||(x_first, x_first+1)|| <= radius (radius >= 0).
      void
      add_disc(size_type first, double radius);
      /// (y_1/a)^2 + (y_2/b)^2 <= 1, y = R(-angle) (x_first, x_first+1):
      /// semi-axis a along the direction at @p angle (radians) from the
      /// first unknown's axis, b perpendicular to it.  a, b > 0.
      void
      add_ellipse(size_type first, double a, double b, double angle = 0.);
      /// ||(x_first+1, x_first+2)|| <= mu x_first, mu >= 0.
      void
      add_cone(size_type first, double mu);

      /**
       * Map the blocks to the locally owned part of @p layout; throws if a
       * block straddles ranks, overlaps another block, or lies outside the
       * vector.  May be called again for another layout.
       */
      void
      finalize(const VectorType &layout);

      bool
      is_finalized() const;

      /**
       * After finalize(): the radius of disc block @p k (in the order the
       * discs were added) becomes @p radius (>= 0).  A Coulomb fixed point
       * changes only the slip bounds from one Tresca QP to the next; this
       * spares it a new set with its set-up (placement checks, sorting,
       * runs), which on a small contact problem costs as much as a QP
       * iteration.  A disc owned by another rank is ignored.
       */
      void
      set_disc_radius(size_type k, double radius);

      /// After finalize(): the bounds of box block @p k (in the order the
      /// boxes were added), lower <= upper; see set_disc_radius().
      void
      set_box_bounds(size_type k, double lower, double upper);

      double
      active_tolerance() const;

      /// Global number of blocks (all types), after finalize().
      size_type
      n_blocks() const;
      /// Global number of blocks of one type, after finalize().
      size_type
      n_blocks(BlockType type) const;
      /// True if every block is a bound or box (what MPRGP accepts).
      bool
      only_bounds_and_boxes() const;
      /// Global number of unknowns in blocks (the rest of x is
      /// unconstrained), after finalize().
      size_type
      n_constrained_unknowns() const;

      /**
       * Calls @p f(index, lower, upper) for every bound block (upper =
       * +infinity), then for every box block, in the order they were added
       * (global indices, current bounds): the constraints as rows for a
       * solver of general linear inequalities (CGCSolver).
       */
      template <typename Function>
      void
      for_each_bound_and_box(const Function &f) const
      {
        for (const Placed<blocks::Bound> &placed : added_bounds)
          f(placed.first,
            placed.block.lower,
            std::numeric_limits<double>::infinity());
        for (const Placed<blocks::Box> &placed : added_boxes)
          f(placed.first, placed.block.lower, placed.block.upper);
      }

      /// x := P_Omega(x), the Euclidean projection, block by block.
      void
      project(VectorType &x) const;
      /// dst := P_Omega(src).
      void
      project(const VectorType &src, VectorType &dst) const;

      /// ||x - P(x)||: Euclidean distance of x from Omega.
      double
      feasibility_violation(const VectorType &x) const;

      /// Largest alpha >= 0 with x - alpha p in Omega (x feasible);
      /// +infinity if the ray never leaves Omega.
      double
      max_feasible_step(const VectorType &x, const VectorType &p) const;

      /**
       * x := x - alpha p for 0 <= alpha <= max_feasible_step(x, p) (the CG
       * half-step), with the blocks that reach their boundary put exactly
       * on it (rounding would otherwise leave a bound 1e-17 away from l
       * and the block would not count as active) and any rounding
       * overshoot projected back.
       */
      void
      feasible_step(VectorType &x, const VectorType &p, double alpha) const;

      /// phi(x), beta(x) for gradient g at x (either output may be the same
      /// object as @p g only for split into one of them -- do not alias).
      void
      split_gradient(const VectorType &x,
                     const VectorType &g,
                     VectorType       &free_gradient,
                     VectorType       &chopped_gradient) const;
      /// phi(x)
      void
      free_gradient(const VectorType &x,
                    const VectorType &g,
                    VectorType       &free_gradient) const;
      /// beta(x)
      void
      chopped_gradient(const VectorType &x,
                       const VectorType &g,
                       VectorType       &chopped_gradient) const;
      /// g^P(x) = phi + beta
      void
      projected_gradient(const VectorType &x,
                         const VectorType &g,
                         VectorType       &projected_gradient) const;
      /// g~_alpha(x) = (x - P(x - alpha g)) / alpha
      void
      reduced_gradient(const VectorType &x,
                       const VectorType &g,
                       double            alpha,
                       VectorType       &reduced_gradient) const;
      /// g~^P_alpha(x) = phi + beta~_alpha
      void
      reduced_projected_gradient(const VectorType &x,
                                 const VectorType &g,
                                 double            alpha,
                                 VectorType       &reduced_projected) const;

      /// ||phi||^2 and ||beta||^2 in one sweep, no vectors written.
      GradientNorms
      gradient_norms(const VectorType &x, const VectorType &g) const;

      /**
       * @name Fused passes of the active-set solvers
       * Each does in one pass over the vectors what the separate calls
       * above do in two to four: on the membrane (a 5-point stencil) a
       * vector pass costs a third of a Hessian product, so the number of
       * passes, not the arithmetic, is the solver's overhead.  Same
       * results as the separate calls up to the order of summation.
       */
      ///@{
      /**
       * The CG step: x -= alpha p, g -= alpha Ap, and at the new x the
       * squared norms of phi and beta and @p phi_dot_Ap = phi'Ap (the
       * numerator of the CG coefficient).  phi is not stored:
       * conjugate_direction() recomputes it from x and g.  With
       * @p reduced_alpha > 0 also the reduced chopped gradient's squared
       * norm for that step length (reduced_gradient_norms(); MwPGP's
       * test), else that field is 0.
       */
      GradientNorms
      cg_step(VectorType       &x,
              VectorType       &g,
              const VectorType &p,
              const VectorType &Ap,
              double            alpha,
              double           &phi_dot_Ap,
              double            reduced_alpha = 0.) const;

      /// What conjugate_direction() measures of the new direction.
      struct Direction
      {
        /// max_feasible_step(x, p)
        double max_step = 0.;
        /// p'p
        double pp = 0.;
        /// g'p
        double gp = 0.;
      };

      /**
       * p := phi(x, g) - beta p (the new conjugate direction; beta = 0
       * restarts with p = phi), with max_feasible_step(x, p), p'p, g'p of
       * the new p.
       */
      Direction
      conjugate_direction(const VectorType &x,
                          const VectorType &g,
                          double            beta,
                          VectorType       &p) const;

      /**
       * x := P(x - alpha d) with d = g, or d = phi(x, g) when
       * @p free_only (MPRGP's expansion along the free gradient).
       * @p g must not be @p x.
       */
      void
      projected_step(VectorType       &x,
                     const VectorType &g,
                     double            alpha,
                     bool              free_only) const;
      ///@}
      /// free_gradient() and gradient_norms() in one pass (what an
      /// active-set iteration needs after every step); @p phi must not be
      /// @p g.
      GradientNorms
      free_gradient_and_norms(const VectorType &x,
                              const VectorType &g,
                              VectorType       &phi) const;
      /// As gradient_norms(), plus ||beta~_alpha||^2.
      GradientNorms
      reduced_gradient_norms(const VectorType &x,
                             const VectorType &g,
                             double            alpha) const;
      /// ||g~_alpha(x)|| without writing a vector.
      double
      reduced_gradient_norm(const VectorType &x,
                            const VectorType &g,
                            double            alpha) const;

      /// v := 0 on the unknowns of active blocks (keeps v on the free set):
      /// turns g into phi, or restricts a CG direction to the free set.
      void
      zero_active(const VectorType &x, VectorType &v) const;

      /// mask := 1 on unknowns of active blocks, 0 elsewhere.
      void
      active_mask(const VectorType &x, VectorType &mask) const;

      /// Global number of active blocks per BlockType (index by
      /// static_cast<unsigned>(type)).
      std::array<size_type, n_block_types>
      n_active_blocks(const VectorType &x) const;

      /// Is the (locally owned) block containing global index @p first
      /// active at x?  Throws if no local block starts at @p first.
      bool
      is_active(const VectorType &x, size_type first) const;

      /**
       * Complementarity measure sum_j mu_j dist_j: mu_j >= 0 is the
       * multiplier estimate -n_j'g_j (n_j the outward normal at the point
       * of the boundary nearest to x_j), dist_j the distance of x_j to that
       * boundary.  Zero at a KKT point.
       */
      double
      complementarity(const VectorType &x, const VectorType &g) const;

    private:
      /// A block of kind Block whose first unknown is @p first: the global
      /// index as added, the local offset into v.begin() after finalize().
      template <typename Block>
      struct Placed
      {
        size_type first;
        Block     block;
      };

      /**
       * f(blocks) for the list of placed blocks of every kind, in the
       * order of BlockType: every pass over the blocks visits them in this
       * order, which is the order of its sums.
       */
      template <typename Function>
      void
      for_each_kind(const Function &f) const
      {
        f(bounds);
        f(boxes);
        f(discs);
        f(ellipses);
        f(cones);
      }

      /// for_each_kind() over the disc, ellipse and cone blocks only (the
      /// bounds and boxes have passes over runs of their own)
      template <typename Function>
      void
      for_each_curved_kind(const Function &f) const
      {
        f(discs);
        f(ellipses);
        f(cones);
      }

      /**
       * One sweep over the blocks of the kinds from @p first_kind on (in
       * BlockType order) computing the free/chopped split (thesis 1.31)
       * phi_j, beta_j and, with @p reduced, beta~_alpha_j (thesis 1.4.3),
       * handed to sink(offset, width, phi, beta, reduced_beta); the
       * gradient functions are built on it.  (The hot paths treat the
       * bounds, or the bounds and boxes, in their own loops over runs,
       * the bounds' in VectorKernels, and start the sweep after them.)
       */
      template <typename Sink>
      void
      sweep(const VectorType &x,
            const VectorType &g,
            double            alpha,
            bool              reduced,
            Sink             &sink,
            BlockType         first_kind = BlockType::bound) const;

      /// max_feasible_step() over the disc, ellipse and cone blocks only,
      /// local (no reduction); v, d: local entries of x and p
      double
      curved_max_step(const double *v, const double *d) const;

      /// project() on the disc, ellipse and cone blocks only (local)
      void
      project_curved(double *v) const;

      /// true if there are disc, ellipse or cone blocks on this rank
      bool
      has_curved_blocks() const;

      /// gradient_norms() (and with @p phi the free gradient's local
      /// entries written there: free_gradient_and_norms()) or, with
      /// @p reduced, reduced_gradient_norms() for the step length alpha
      GradientNorms
      norms(const VectorType &x,
            const VectorType &g,
            double            alpha,
            bool              reduced,
            double           *phi = nullptr) const;

      double tolerance;
      bool   finalized = false;

      // as added (global indices)
      std::vector<Placed<blocks::Bound>>   added_bounds;
      std::vector<Placed<blocks::Box>>     added_boxes;
      std::vector<Placed<blocks::Disc>>    added_discs;
      std::vector<Placed<blocks::Ellipse>> added_ellipses;
      std::vector<Placed<blocks::Cone>>    added_cones;

      // after finalize: locally owned blocks at local offsets, sorted by
      // offset, kind by kind so that each operation is a tight loop
      // without dispatch.
      std::vector<Placed<blocks::Bound>>   bounds;
      std::vector<Placed<blocks::Box>>     boxes;
      std::vector<Placed<blocks::Disc>>    discs;
      std::vector<Placed<blocks::Ellipse>> ellipses;
      std::vector<Placed<blocks::Cone>>    cones;

      /// A maximal set of bound (or box) blocks at consecutive local
      /// offsets [begin, begin + count); `first` indexes the kind's
      /// vectors (bounds and bound_lower, or boxes).  In the dual contact
      /// problem all normal multipliers form one run, so the hot loops
      /// (norms, free gradient, steps) are plain streaming loops without
      /// indirection or unpredictable branches.
      struct Run
      {
        std::size_t begin, count, first;
      };
      std::vector<Run> bound_runs, box_runs;
      /// the bounds' l, contiguous for VectorKernels
      std::vector<double> bound_lower;
      /// unconstrained local entries, as ranges [first, second)
      std::vector<std::pair<std::size_t, std::size_t>> free_ranges;

      std::array<size_type, n_block_types> global_counts{};
      dealii::IndexSet                     owned;
      std::size_t                          local_size = 0;
    };


    template <typename VectorType>
    template <typename Sink>
    void
    SeparableSet<VectorType>::sweep(const VectorType &x,
                                    const VectorType &g,
                                    const double      alpha,
                                    const bool        reduced,
                                    Sink             &sink,
                                    const BlockType   first_kind) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      const double *v     = x.begin();
      const double *gv    = g.begin();
      const auto    split = [&](const auto &placed_blocks)
      {
        using Block = decltype(placed_blocks[0].block);
        using Kind  = std::remove_const_t<std::remove_reference_t<Block>>;
        constexpr unsigned int width = Kind::n_components;
        if (Kind::type < first_kind)
          return;
        // red is only written with `reduced` (and only read then)
        double phi[width], beta[width], red[width] = {};
        for (const auto &placed : placed_blocks)
        {
          const Kind   &block = placed.block;
          const double *y = v + placed.first, *gj = gv + placed.first;
          const auto    state = block.classify(y, tolerance);
          if (!state.active)
            for (unsigned int c = 0; c < width; ++c)
            {
              phi[c]  = gj[c];
              beta[c] = red[c] = 0.;
            }
          else
          {
            for (unsigned int c = 0; c < width; ++c)
              phi[c] = 0.;
            block.chopped_gradient(y, gj, state, beta);
            if (reduced)
              block.reduced_chopped_gradient(y, gj, alpha, state, red);
          }
          sink(placed.first, width, phi, beta, red);
        }
      };
      for_each_kind(split);
    }
  } // namespace qp
} // namespace dualcontact

#endif
