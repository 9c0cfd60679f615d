/**
 * @file separable_set_steps.cc
 * SeparableSet: the projection and the steps (largest feasible step, the
 * CG half-step that lands on the boundary, the projected step).  Bounds
 * and boxes are treated in loops over their runs (the bounds' in
 * VectorKernels), the other kinds block by block; each block's arithmetic
 * is its kind's (qp/blocks/).
 */
#include <qp/separable_set.h>
#include <qp/vector_helpers.h>
#include <qp/vector_kernels.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dualcontact
{
  namespace qp
  {
    namespace
    {
      /// f(box, i) for every box block in @p runs of @p boxes (the set's
      /// box_runs and boxes), i its local offset, in the runs' order
      template <typename Runs, typename Boxes, typename Function>
      void
      for_each_box(const Runs &runs, const Boxes &boxes, const Function &f)
      {
        for (const auto &run : runs)
          for (std::size_t i = 0; i < run.count; ++i)
            f(boxes[run.first + i].block, run.begin + i);
      }
    } // namespace


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
          blocks::Bound{l[i]}.project(y + i);
      }
      for_each_box(box_runs,
                   boxes,
                   [v](const blocks::Box &box, const std::size_t i)
                   { box.project(v + i); });
      project_curved(v);
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::project_curved(double *v) const
    {
      for_each_curved_kind(
        [v](const auto &placed_blocks)
        {
          for (const auto &placed : placed_blocks)
            placed.block.project(v + placed.first);
        });
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
      for_each_kind(
        [v, &sum](const auto &placed_blocks)
        {
          for (const auto &placed : placed_blocks)
            sum += placed.block.distance_squared(v + placed.first);
        });
      return std::sqrt(internal::sum(sum, x));
    }


    template <typename VectorType>
    double
    SeparableSet<VectorType>::max_feasible_step(const VectorType &x,
                                                const VectorType &p) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      const double *v = x.begin();
      const double *d = p.begin();
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
      blocks::MinRatio box_ratio{ratio.num[0], ratio.den[0]};
      for_each_box(box_runs,
                   boxes,
                   [v, d, &box_ratio](const blocks::Box &box,
                                      const std::size_t  i)
                   { box.offer_step(v + i, d + i, box_ratio); });
      double alpha = VectorKernels::min_ratio(ratio);
      alpha        = std::min(alpha, curved_max_step(v, d));
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
      double alpha = std::numeric_limits<double>::infinity();
      for_each_curved_kind(
        [v, d, &alpha](const auto &placed_blocks)
        {
          for (const auto &placed : placed_blocks)
            alpha = std::min(alpha,
                             placed.block.max_step(v + placed.first,
                                                   d + placed.first));
        });
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
      // one pass: x -= alpha p, bounds and boxes put on the bound they
      // land on, the other kinds projected back from any rounding
      // overshoot
      for (const auto &range : free_ranges)
        for (std::size_t i = range.first; i < range.second; ++i)
          v[i] -= alpha * d[i];
      for (const Run &run : bound_runs)
        VectorKernels::feasible_step(run.count,
                                     v + run.begin,
                                     d + run.begin,
                                     bound_lower.data() + run.first,
                                     alpha);
      for_each_box(box_runs,
                   boxes,
                   [v, d, alpha](const blocks::Box &box, const std::size_t i)
                   { box.feasible_step(v + i, d + i, alpha); });
      for_each_curved_kind(
        [v, d, alpha](const auto &placed_blocks)
        {
          for (const auto &placed : placed_blocks)
            placed.block.feasible_step(v + placed.first,
                                       d + placed.first,
                                       alpha);
        });
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
      // the step along phi (free_only: none on a block active at x) or
      // g, then the block's projection
      const auto step = [&](const auto &block, double *y, const double *gj)
      {
        const bool active = free_only && block.classify(y, tolerance).active;
        for (unsigned int c = 0; c < block.n_components; ++c)
          y[c] -= alpha * (active ? 0. : gj[c]);
        block.project(y);
      };
      for_each_box(box_runs,
                   boxes,
                   [&](const blocks::Box &box, const std::size_t i)
                   { step(box, v + i, gv + i); });
      for_each_curved_kind(
        [&](const auto &placed_blocks)
        {
          for (const auto &placed : placed_blocks)
            step(placed.block, v + placed.first, gv + placed.first);
        });
    }


#define DUALCONTACT_INSTANTIATE_SET_STEPS(V)                                    \
  template void   SeparableSet<V>::project(V &) const;                          \
  template void   SeparableSet<V>::project_curved(double *) const;              \
  template void   SeparableSet<V>::project(const V &, V &) const;               \
  template double SeparableSet<V>::feasibility_violation(const V &) const;      \
  template double SeparableSet<V>::max_feasible_step(const V &, const V &)      \
    const;                                                                      \
  template bool   SeparableSet<V>::has_curved_blocks() const;                   \
  template double SeparableSet<V>::curved_max_step(const double *,              \
                                                   const double *) const;       \
  template void   SeparableSet<V>::feasible_step(V &, const V &, double) const; \
  template void   SeparableSet<V>::projected_step(V &, const V &, double, bool) \
    const;

    DUALCONTACT_INSTANTIATE_SET_STEPS(dealii::Vector<double>)
    DUALCONTACT_INSTANTIATE_SET_STEPS(dealii::TrilinosWrappers::MPI::Vector)
  } // namespace qp
} // namespace dualcontact
