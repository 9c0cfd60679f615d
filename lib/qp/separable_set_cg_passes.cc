/**
 * @file separable_set_cg_passes.cc
 * SeparableSet: the fused passes of the active-set solvers' CG steps
 * (cg_step, conjugate_direction), each one pass over the vectors that does
 * what the step, the gradient split and the norms do in two to four.  The
 * runs of bounds go to VectorKernels, the boxes' runs are loops of their
 * own, the other kinds are stepped and then split by the sweep.
 */
#include <qp/separable_set.h>
#include <qp/vector_helpers.h>
#include <qp/vector_kernels.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>

namespace dualcontact
{
  namespace qp
  {
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
      for (const Run &run : box_runs)
      {
        double       *y   = v + run.begin;
        double       *q   = gv + run.begin;
        const double *d   = pv + run.begin;
        const double *a   = av + run.begin;
        const auto   *box = boxes.data() + run.first;
        for (std::size_t i = 0; i < run.count; ++i)
        {
          y[i] -= alpha * d[i];
          q[i] -= alpha * a[i];
          const auto state = box[i].block.classify(y + i, tolerance);
          double     c;
          box[i].block.chopped_gradient(y + i, q + i, state, &c);
          fsq += state.active ? 0. : q[i] * q[i];
          bsq += c * c;
          pa += state.active ? 0. : q[i] * a[i];
          if (reduced && state.active)
          {
            double red;
            box[i].block.reduced_chopped_gradient(
              y + i, q + i, reduced_alpha, state, &red);
            rsq += red * red;
          }
        }
      }
      if (has_curved_blocks())
      {
        for_each_curved_kind(
          [&](const auto &placed_blocks)
          {
            for (const auto &placed : placed_blocks)
              for (unsigned int c = 0; c < placed.block.n_components; ++c)
              {
                v[placed.first + c] -= alpha * pv[placed.first + c];
                gv[placed.first + c] -= alpha * av[placed.first + c];
              }
          });
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
        sweep(
          x, g, reduced ? reduced_alpha : 1., reduced, sink, BlockType::disc);
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
      blocks::MinRatio box_ratio{ratio.num[0], ratio.den[0]};
      for (const Run &run : box_runs)
      {
        const double *y   = v + run.begin;
        const double *q   = gv + run.begin;
        double       *d   = pv + run.begin;
        const auto   *box = boxes.data() + run.first;
        for (std::size_t i = 0; i < run.count; ++i)
        {
          const auto   state = box[i].block.classify(y + i, tolerance);
          const double di    = (state.active ? 0. : q[i]) - beta * d[i];
          d[i]               = di;
          pp0 += di * di;
          gp0 += q[i] * di;
          box[i].block.offer_step(y + i, d + i, box_ratio);
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
        sweep(x, g, 1., false, sink, BlockType::disc);
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


#define DUALCONTACT_INSTANTIATE_SET_CG_PASSES(V)                          \
  template GradientNorms SeparableSet<V>::cg_step(                        \
    V &, V &, const V &, const V &, double, double &, double) const;      \
  template typename SeparableSet<V>::Direction                            \
  SeparableSet<V>::conjugate_direction(const V &, const V &, double, V &) \
    const;

    DUALCONTACT_INSTANTIATE_SET_CG_PASSES(dealii::Vector<double>)
    DUALCONTACT_INSTANTIATE_SET_CG_PASSES(dealii::TrilinosWrappers::MPI::Vector)
  } // namespace qp
} // namespace dualcontact
