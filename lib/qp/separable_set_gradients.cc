/**
 * @file separable_set_gradients.cc
 * SeparableSet: the free/chopped split of the gradient (thesis 1.31), the
 * reduced gradients (thesis 1.33, 1.4.3), their squared norms in one sweep,
 * the free part of any vector (zero_active, active_mask) and the
 * complementarity measure.  Each block's part is its kind's
 * (qp/blocks/); the sweep (separable_set.h) visits the kinds in BlockType
 * order, the norms treat the runs of bounds and boxes in loops of their
 * own (the bounds' in VectorKernels).
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
    namespace
    {
      /// ||x_j - P_j(x_j - alpha g_j)||^2 of one block: alpha^2 times its
      /// part of the reduced gradient's squared norm
      template <typename Block>
      double
      projected_step_squared(const Block  &block,
                             const double *x,
                             const double *g,
                             const double  alpha)
      {
        constexpr unsigned int width = Block::n_components;
        double                 z[width];
        for (unsigned int c = 0; c < width; ++c)
          z[c] = x[c] - alpha * g[c];
        block.project(z);
        double sum = blocks::square(x[0] - z[0]);
        for (unsigned int c = 1; c < width; ++c)
          sum += blocks::square(x[c] - z[c]);
        return sum;
      }

      /// A sink for SeparableSet's sweep that writes part(phi, beta,
      /// reduced beta) of every component of a block to @p out.
      template <typename Part>
      auto
      writer(double *out, const Part &part)
      {
        return [out, part](const auto     offset,
                           const unsigned width,
                           const double  *phi,
                           const double  *beta,
                           const double  *reduced)
        {
          for (unsigned c = 0; c < width; ++c)
            out[offset + c] = part(phi[c], beta[c], reduced[c]);
        };
      }
    } // namespace


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
          f[i] =
            blocks::Bound{l[i]}.classify(y + i, tolerance).active ? 0. : f[i];
      }
      for (const Run &run : box_runs)
      {
        const double *y   = v + run.begin;
        double       *f   = o + run.begin;
        const auto   *box = boxes.data() + run.first;
        for (std::size_t i = 0; i < run.count; ++i)
          f[i] = box[i].block.classify(y + i, tolerance).active ? 0. : f[i];
      }
      auto sink = writer(o, [](double phi, double, double) { return phi; });
      sweep(x, g, 1., false, sink, BlockType::disc);
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::chopped_gradient(const VectorType &x,
                                               const VectorType &g,
                                               VectorType       &out) const
    {
      out = 0.;
      auto sink =
        writer(out.begin(), [](double, double beta, double) { return beta; });
      sweep(x, g, 1., false, sink);
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::projected_gradient(const VectorType &x,
                                                 const VectorType &g,
                                                 VectorType       &out) const
    {
      out = g;
      auto sink =
        writer(out.begin(),
               [](double phi, double beta, double) { return phi + beta; });
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
      out       = g;
      auto sink = writer(out.begin(),
                         [](double phi, double, double reduced)
                         { return phi + reduced; });
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
        sweep(x, g, alpha, true, sink, BlockType::box);
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
        for (const Run &run : box_runs)
        {
          const double *y   = v + run.begin;
          const double *q   = gv + run.begin;
          const auto   *box = boxes.data() + run.first;
          double        f = 0., b = 0.;
          for (std::size_t i = 0; i < run.count; ++i)
          {
            const auto state = box[i].block.classify(y + i, tolerance);
            double     c;
            box[i].block.chopped_gradient(y + i, q + i, state, &c);
            if (phi != nullptr)
              phi[run.begin + i] = state.active ? 0. : q[i];
            f += state.active ? 0. : q[i] * q[i];
            b += c * c;
          }
          fsq += f;
          bsq += b;
        }
        sweep(x, g, 1., false, sink, BlockType::disc);
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
      double        free = 0., sum = 0.;
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
          b += projected_step_squared(blocks::Bound{l[i]}, y + i, q + i, alpha);
        sum += b / (alpha * alpha);
      }
      for (const Run &run : box_runs)
      {
        const double *y   = v + run.begin;
        const double *q   = gv + run.begin;
        const auto   *box = boxes.data() + run.first;
        double        b   = 0.;
        for (std::size_t i = 0; i < run.count; ++i)
          b += projected_step_squared(box[i].block, y + i, q + i, alpha);
        sum += b / (alpha * alpha);
      }
      for_each_curved_kind(
        [&](const auto &placed_blocks)
        {
          for (const auto &placed : placed_blocks)
            sum += projected_step_squared(placed.block,
                                          v + placed.first,
                                          gv + placed.first,
                                          alpha) /
                   (alpha * alpha);
        });
      return std::sqrt(internal::sum(free + sum, x));
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
      for_each_kind(
        [&](const auto &placed_blocks)
        {
          for (const auto &placed : placed_blocks)
            sum +=
              placed.block.complementarity(v + placed.first, gv + placed.first);
        });
      return internal::sum(sum, x);
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::zero_active(const VectorType &x,
                                          VectorType       &v) const
    {
      // phi of v (taken as a "gradient") is v on free blocks and 0 on
      // active ones; the sweep reads a block before the sink writes it
      auto sink =
        writer(v.begin(), [](double phi, double, double) { return phi; });
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


#define DUALCONTACT_INSTANTIATE_SET_GRADIENTS(V)                                 \
  template void SeparableSet<V>::split_gradient(const V &,                       \
                                                const V &,                       \
                                                V &,                             \
                                                V &) const;                      \
  template void SeparableSet<V>::free_gradient(const V &, const V &, V &)        \
    const;                                                                       \
  template void SeparableSet<V>::chopped_gradient(const V &, const V &, V &)     \
    const;                                                                       \
  template void SeparableSet<V>::projected_gradient(const V &, const V &, V &)   \
    const;                                                                       \
  template void          SeparableSet<V>::reduced_gradient(const V &,            \
                                                  const V &,            \
                                                  double,               \
                                                  V &) const;           \
  template void          SeparableSet<V>::reduced_projected_gradient(const V &,  \
                                                            const V &,  \
                                                            double,     \
                                                            V &) const; \
  template GradientNorms SeparableSet<V>::gradient_norms(const V &, const V &)   \
    const;                                                                       \
  template GradientNorms SeparableSet<V>::free_gradient_and_norms(const V &,     \
                                                                  const V &,     \
                                                                  V &) const;    \
  template GradientNorms SeparableSet<V>::reduced_gradient_norms(const V &,      \
                                                                 const V &,      \
                                                                 double)         \
    const;                                                                       \
  template GradientNorms SeparableSet<V>::norms(                                 \
    const V &, const V &, double, bool, double *) const;                         \
  template double SeparableSet<V>::reduced_gradient_norm(const V &,              \
                                                         const V &,              \
                                                         double) const;          \
  template double SeparableSet<V>::complementarity(const V &, const V &)         \
    const;                                                                       \
  template void SeparableSet<V>::zero_active(const V &, V &) const;              \
  template void SeparableSet<V>::active_mask(const V &, V &) const;

    DUALCONTACT_INSTANTIATE_SET_GRADIENTS(dealii::Vector<double>)
    DUALCONTACT_INSTANTIATE_SET_GRADIENTS(dealii::TrilinosWrappers::MPI::Vector)
  } // namespace qp
} // namespace dualcontact
