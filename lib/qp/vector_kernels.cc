#include <qp/vector_kernels.h>

#include <cmath>
#include <cstring>
#include <limits>

// One clone per instruction set on x86-64 with GCC (the loader's ifunc
// resolver picks one at start-up); elsewhere one portable build of the
// same code.
// (DUALCONTACT_KERNEL_NO_CLONES: one build for the compiler's -march, to
// compare the instruction sets' results with the test on one machine.)
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
  !defined(DUALCONTACT_KERNEL_NO_CLONES)
#define DUALCONTACT_KERNEL_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#define DUALCONTACT_KERNEL_CLONED 1
#else
#define DUALCONTACT_KERNEL_CLONES
#define DUALCONTACT_KERNEL_CLONED 0
#endif

#define DUALCONTACT_INLINE inline __attribute__((always_inline))

namespace dualcontact
{
  namespace qp
  {
    namespace
    {
      // W doubles, one lane each; comparisons give a mask of longs.  Four
      // (one AVX2 register; GCC lowers it to two SSE2 registers in the
      // baseline clone): vectors of eight (one AVX-512 register) ran
      // slower on the development machine.
      template <int W>
      struct V;
      template <>
      struct V<4>
      {
        typedef double d __attribute__((vector_size(32)));
        typedef long   m __attribute__((vector_size(32)));
      };
      template <>
      struct V<8>
      {
        typedef double d __attribute__((vector_size(64)));
        typedef long   m __attribute__((vector_size(64)));
      };

      template <typename D>
      DUALCONTACT_INLINE D
      load(const double *a)
      {
        D r;
        std::memcpy(&r, a, sizeof(r));
        return r;
      }

      template <typename D>
      DUALCONTACT_INLINE void
      store(double *a, const D v)
      {
        std::memcpy(a, &v, sizeof(v));
      }

      // mask ? v : 0 and mask ? 0 : v as bitwise and / and-not (one
      // instruction where a blend takes two); the same bits as the
      // conditional (+0. where dropped)
      template <typename D, typename M>
      DUALCONTACT_INLINE D
      keep(const M mask, const D v)
      {
        return (D)((M)v & mask);
      }

      template <typename D, typename M>
      DUALCONTACT_INLINE D
      drop(const M mask, const D v)
      {
        return (D)((M)v & ~mask);
      }

      // Eight lanes: lane j takes the entries i = j (mod 8) of a run, in
      // two vectors of four; a remainder of four to seven entries gives
      // its first four to lanes 0-3, and the last one to three entries go
      // to lane 0.  The loop bodies' expressions are those of the scalar
      // remainder loops (and of
      // SeparableSet's loops for boxes): std::abs(l) as l < 0 ? -l : l,
      // std::min(g, 0.) as 0. < g ? 0. : g, std::max(r, 0.) as r < 0. ?
      // 0. : r.
      using D4 = V<4>::d;
      using D8 = V<8>::d;

      template <typename D>
      DUALCONTACT_INLINE void
      dots_body(const std::size_t i,
                const double     *p,
                const double     *Ap,
                const double     *g,
                D                &s0,
                D                &s1,
                D                &s2)
      {
        const D pv = load<D>(p + i), av = load<D>(Ap + i), gv = load<D>(g + i);
        s0 += pv * av;
        s1 += pv * pv;
        s2 += gv * pv;
      }

      template <typename D>
      DUALCONTACT_INLINE void
      cg_step_body(const std::size_t i,
                   double           *x,
                   double           *g,
                   const double     *p,
                   const double     *Ap,
                   const double     *l,
                   const double      tol,
                   const double      alpha,
                   D                &fs,
                   D                &bs,
                   D                &pa)
      {
        const D av = load<D>(Ap + i), lv = load<D>(l + i);
        const D xv = load<D>(x + i) - alpha * load<D>(p + i);
        const D gv = load<D>(g + i) - alpha * av;
        store(x + i, xv);
        store(g + i, gv);
        const auto active = (xv - lv) <= tol * (lv < 0. ? -lv : lv);
        const D    gm     = drop(0. < gv, gv);
        fs += drop(active, gv * gv);
        bs += keep(active, gm * gm);
        pa += drop(active, gv * av);
      }

      // The smaller of two fractions num/den and other_num/other_den per
      // lane, the first on a tie: SeparableSet's MinRatio::offer() rule
      // "take if other_den > 0 and other_num den < num other_den" without
      // its first test, which the second implies here: num and other_num
      // are >= 0 (max(room, 0), or 1 at the start), den >= 0, so for
      // other_den <= 0 the right side is <= 0 <= the left one (or a NaN),
      // and nothing is taken, as with the test.  (Kept, the test makes GCC
      // 12 unroll the AVX-512 clone into scalar compares.)
      template <typename D>
      DUALCONTACT_INLINE void
      take_smaller(D &num, D &den, const D other_num, const D other_den)
      {
        const auto take = other_num * den < num * other_den;
        num             = take ? other_num : num;
        den             = take ? other_den : den;
      }

      template <typename D>
      DUALCONTACT_INLINE void
      direction_body(const std::size_t i,
                     const double     *x,
                     const double     *g,
                     const double     *l,
                     const double      tol,
                     const double      beta,
                     double           *p,
                     D                &pp,
                     D                &gp,
                     D                &num,
                     D                &den)
      {
        const D xv = load<D>(x + i), gv = load<D>(g + i), lv = load<D>(l + i);
        const D room      = xv - lv;
        const auto active = room <= tol * (lv < 0. ? -lv : lv);
        const D    dv     = drop(active, gv) - beta * load<D>(p + i);
        store(p + i, dv);
        pp += dv * dv;
        gp += gv * dv;
        take_smaller(num, den, drop(room < 0., room), dv);
      }

      template <typename D>
      DUALCONTACT_INLINE void
      gradient_norms_body(const std::size_t i,
                          const double     *x,
                          const double     *g,
                          const double     *l,
                          const double      tol,
                          double           *phi,
                          D                &fs,
                          D                &bs)
      {
        const D xv = load<D>(x + i), gv = load<D>(g + i), lv = load<D>(l + i);
        const auto active = (xv - lv) <= tol * (lv < 0. ? -lv : lv);
        const D    gm     = drop(0. < gv, gv);
        if (phi != nullptr)
          store(phi + i, drop(active, gv));
        fs += drop(active, gv * gv);
        bs += keep(active, gm * gm);
      }

      template <typename D>
      DUALCONTACT_INLINE void
      max_step_body(const std::size_t i,
                    const double     *x,
                    const double     *p,
                    const double     *l,
                    D                &num,
                    D                &den)
      {
        const D room = load<D>(x + i) - load<D>(l + i);
        take_smaller(num, den, drop(room < 0., room), load<D>(p + i));
      }

      // |y| as y < 0 ? -y : y (std::abs)
      template <typename D>
      DUALCONTACT_INLINE D
      absolute(const D y)
      {
        return y < 0. ? -y : y;
      }

      template <typename D>
      DUALCONTACT_INLINE void
      feasible_step_body(const std::size_t i,
                         double           *x,
                         const double     *p,
                         const double     *l,
                         const double      alpha)
      {
        constexpr double eps8  = 8. * std::numeric_limits<double>::epsilon();
        const D          lv    = load<D>(l + i);
        const D          ap    = alpha * load<D>(p + i);
        const D          y     = load<D>(x + i) - ap;
        const D          scale = (absolute(y) + absolute(ap)) + absolute(lv);
        // (y < l or snapped) ? l : y, as two selections: GCC 12 turns a
        // selection on the or of two masks into scalar code for AVX-512
        const D below = y < lv ? lv : y;
        store(x + i, absolute(y - lv) <= eps8 * scale ? lv : below);
      }

      template <typename D>
      DUALCONTACT_INLINE void
      projected_step_body(const std::size_t i,
                          double           *x,
                          const double     *g,
                          const double     *l,
                          const double      tol,
                          const double      alpha,
                          const bool        free_only)
      {
        const D xv = load<D>(x + i), lv = load<D>(l + i);
        D       step = alpha * load<D>(g + i);
        if (free_only)
          step = drop((xv - lv) <= tol * absolute(lv), step);
        const D y = xv - step;
        store(x + i, y < lv ? lv : y);
      }

      // y (g - b) into the lanes, with g := g - b first when Residual
      template <bool residual>
      DUALCONTACT_INLINE void
      cost_loop(const std::size_t n,
                const double     *y,
                const double     *b,
                double           *g,
                double (&sum)[8])
      {
        D4          s0 = load<D4>(sum), s1 = load<D4>(sum + 4);
        std::size_t i    = 0;
        const auto  body = [&](const std::size_t k, D4 &s)
        {
          const D4 bv = load<D4>(b + k);
          D4       gv = load<D4>(g + k);
          if (residual)
          {
            gv -= bv;
            store(g + k, gv);
          }
          s += load<D4>(y + k) * (gv - bv);
        };
        for (; i + 8 <= n; i += 8)
        {
          body(i, s0);
          body(i + 4, s1);
        }
        if (i + 4 <= n)
        {
          body(i, s0);
          i += 4;
        }
        store(sum, s0);
        store(sum + 4, s1);
        for (; i < n; ++i)
        {
          if (residual)
            g[i] -= b[i];
          sum[0] += y[i] * (g[i] - b[i]);
        }
      }

      template <typename D>
      DUALCONTACT_INLINE void
      differences_body(const std::size_t i,
                       const double     *x,
                       const double     *g,
                       double           *x_prev,
                       double           *g_prev,
                       const bool        copy,
                       D                &ss,
                       D                &sy)
      {
        const D xv = load<D>(x + i), gv = load<D>(g + i);
        const D sv = xv - load<D>(x_prev + i), yv = gv - load<D>(g_prev + i);
        ss += sv * sv;
        sy += sv * yv;
        if (copy)
        {
          store(x_prev + i, xv);
          store(g_prev + i, gv);
        }
      }

      template <typename D>
      DUALCONTACT_INLINE void
      reduced_norms_body(const std::size_t i,
                         const double     *x,
                         const double     *g,
                         const double     *l,
                         const double      tol,
                         const double      alpha,
                         D                &fs,
                         D                &bs,
                         D                &rs)
      {
        const D xv = load<D>(x + i), gv = load<D>(g + i), lv = load<D>(l + i);
        const auto active = (xv - lv) <= tol * (lv < 0. ? -lv : lv);
        const D    gm     = drop(0. < gv, gv);
        // std::max(l, t) = l < t ? t : l
        const D t   = xv - alpha * gv;
        const D m   = lv < t ? t : lv;
        const D red = gv < 0. ? gv : (xv - m) / alpha;
        fs += drop(active, gv * gv);
        bs += keep(active, gm * gm);
        rs += keep(active, red * red);
      }

    } // namespace


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::dots(const std::size_t n,
                        const double     *p,
                        const double     *Ap,
                        const double     *g,
                        Lanes            &pAp_lanes,
                        Lanes            &pp_lanes,
                        Lanes            &gp_lanes)
    {
      double(&pAp)[8] = pAp_lanes.v;
      double(&pp)[8]  = pp_lanes.v;
      double(&gp)[8]  = gp_lanes.v;
      // lanes 0-3 in a*, 4-7 in b*
      D4 a0 = load<D4>(pAp), a1 = load<D4>(pp), a2 = load<D4>(gp);
      D4 b0 = load<D4>(pAp + 4), b1 = load<D4>(pp + 4), b2 = load<D4>(gp + 4);
      std::size_t i = 0;
      for (; i + 8 <= n; i += 8)
      {
        dots_body(i, p, Ap, g, a0, a1, a2);
        dots_body(i + 4, p, Ap, g, b0, b1, b2);
      }
      if (i + 4 <= n)
      {
        dots_body(i, p, Ap, g, a0, a1, a2);
        i += 4;
      }
      store(pAp, a0);
      store(pp, a1);
      store(gp, a2);
      store(pAp + 4, b0);
      store(pp + 4, b1);
      store(gp + 4, b2);
      for (; i < n; ++i)
      {
        pAp[0] += p[i] * Ap[i];
        pp[0] += p[i] * p[i];
        gp[0] += g[i] * p[i];
      }
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::dot(const std::size_t n,
                       const double     *a,
                       const double     *b,
                       Lanes            &ab_lanes)
    {
      double(&ab)[8] = ab_lanes.v;
      D4          s0 = load<D4>(ab), s1 = load<D4>(ab + 4);
      std::size_t i = 0;
      for (; i + 8 <= n; i += 8)
      {
        s0 += load<D4>(a + i) * load<D4>(b + i);
        s1 += load<D4>(a + i + 4) * load<D4>(b + i + 4);
      }
      if (i + 4 <= n)
      {
        s0 += load<D4>(a + i) * load<D4>(b + i);
        i += 4;
      }
      store(ab, s0);
      store(ab + 4, s1);
      for (; i < n; ++i)
        ab[0] += a[i] * b[i];
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::cg_step(const std::size_t n,
                           double           *x,
                           double           *g,
                           const double     *p,
                           const double     *Ap,
                           const double     *l,
                           const double      tol,
                           const double      alpha,
                           Lanes            &free_sq_lanes,
                           Lanes            &chopped_sq_lanes,
                           Lanes            &phi_Ap_lanes)
    {
      double(&free_sq)[8]    = free_sq_lanes.v;
      double(&chopped_sq)[8] = chopped_sq_lanes.v;
      double(&phi_Ap)[8]     = phi_Ap_lanes.v;
      std::size_t i          = 0;
      {
        D8 a0 = load<D8>(free_sq), a1 = load<D8>(chopped_sq),
           a2 = load<D8>(phi_Ap);
        for (; i + 8 <= n; i += 8)
          cg_step_body(i, x, g, p, Ap, l, tol, alpha, a0, a1, a2);
        store(free_sq, a0);
        store(chopped_sq, a1);
        store(phi_Ap, a2);
      }
      if (i + 4 <= n)
      {
        D4 a0 = load<D4>(free_sq), a1 = load<D4>(chopped_sq),
           a2 = load<D4>(phi_Ap);
        cg_step_body(i, x, g, p, Ap, l, tol, alpha, a0, a1, a2);
        store(free_sq, a0);
        store(chopped_sq, a1);
        store(phi_Ap, a2);
        i += 4;
      }
      for (; i < n; ++i)
      {
        x[i] -= alpha * p[i];
        g[i] -= alpha * Ap[i];
        const bool   active = x[i] - l[i] <= tol * (l[i] < 0. ? -l[i] : l[i]);
        const double gm     = 0. < g[i] ? 0. : g[i];
        free_sq[0] += active ? 0. : g[i] * g[i];
        chopped_sq[0] += active ? gm * gm : 0.;
        phi_Ap[0] += active ? 0. : g[i] * Ap[i];
      }
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::conjugate_direction(const std::size_t n,
                                       const double     *x,
                                       const double     *g,
                                       const double     *l,
                                       const double      tol,
                                       const double      beta,
                                       double           *p,
                                       Lanes            &pp_lanes,
                                       Lanes            &gp_lanes,
                                       RatioLanes       &ratio)
    {
      double(&pp)[8]  = pp_lanes.v;
      double(&gp)[8]  = gp_lanes.v;
      double(&num)[8] = ratio.num;
      double(&den)[8] = ratio.den;
      std::size_t i   = 0;
      {
        D8 a0 = load<D8>(pp), a1 = load<D8>(gp), a2 = load<D8>(num),
           a3 = load<D8>(den);
        D8 c2 = {1., 1., 1., 1., 1., 1., 1., 1.}, c3 = {};
        for (; i + 16 <= n; i += 16)
        {
          direction_body(i, x, g, l, tol, beta, p, a0, a1, a2, a3);
          direction_body(i + 8, x, g, l, tol, beta, p, a0, a1, c2, c3);
        }
        if (i + 8 <= n)
        {
          direction_body(i, x, g, l, tol, beta, p, a0, a1, a2, a3);
          i += 8;
        }
        take_smaller(a2, a3, c2, c3);
        store(pp, a0);
        store(gp, a1);
        store(num, a2);
        store(den, a3);
      }
      if (i + 4 <= n)
      {
        D4 a0 = load<D4>(pp), a1 = load<D4>(gp), a2 = load<D4>(num),
           a3 = load<D4>(den);
        direction_body(i, x, g, l, tol, beta, p, a0, a1, a2, a3);
        store(pp, a0);
        store(gp, a1);
        store(num, a2);
        store(den, a3);
        i += 4;
      }
      for (; i < n; ++i)
      {
        const double room   = x[i] - l[i];
        const bool   active = room <= tol * (l[i] < 0. ? -l[i] : l[i]);
        const double di     = (active ? 0. : g[i]) - beta * p[i];
        p[i]                = di;
        pp[0] += di * di;
        gp[0] += g[i] * di;
        const double r    = room < 0. ? 0. : room;
        const bool   take = r * den[0] < num[0] * di; // see take_smaller
        num[0]            = take ? r : num[0];
        den[0]            = take ? di : den[0];
      }
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::gradient_norms(const std::size_t n,
                                  const double     *x,
                                  const double     *g,
                                  const double     *l,
                                  const double      tol,
                                  double           *phi,
                                  Lanes            &free_sq_lanes,
                                  Lanes            &chopped_sq_lanes)
    {
      double(&free_sq)[8]    = free_sq_lanes.v;
      double(&chopped_sq)[8] = chopped_sq_lanes.v;
      std::size_t i          = 0;
      {
        D8 a0 = load<D8>(free_sq), a1 = load<D8>(chopped_sq);
        for (; i + 8 <= n; i += 8)
          gradient_norms_body(i, x, g, l, tol, phi, a0, a1);
        store(free_sq, a0);
        store(chopped_sq, a1);
      }
      if (i + 4 <= n)
      {
        D4 a0 = load<D4>(free_sq), a1 = load<D4>(chopped_sq);
        gradient_norms_body(i, x, g, l, tol, phi, a0, a1);
        store(free_sq, a0);
        store(chopped_sq, a1);
        i += 4;
      }
      for (; i < n; ++i)
      {
        const bool   active = x[i] - l[i] <= tol * (l[i] < 0. ? -l[i] : l[i]);
        const double gm     = 0. < g[i] ? 0. : g[i];
        if (phi != nullptr)
          phi[i] = active ? 0. : g[i];
        free_sq[0] += active ? 0. : g[i] * g[i];
        chopped_sq[0] += active ? gm * gm : 0.;
      }
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::reduced_norms(const std::size_t n,
                                 const double     *x,
                                 const double     *g,
                                 const double     *l,
                                 const double      tol,
                                 const double      alpha,
                                 Lanes            &free_sq_lanes,
                                 Lanes            &chopped_sq_lanes,
                                 Lanes            &reduced_sq_lanes)
    {
      double(&free_sq)[8]    = free_sq_lanes.v;
      double(&chopped_sq)[8] = chopped_sq_lanes.v;
      double(&reduced_sq)[8] = reduced_sq_lanes.v;
      D4 a0 = load<D4>(free_sq), a1 = load<D4>(chopped_sq),
         a2 = load<D4>(reduced_sq);
      D4 b0 = load<D4>(free_sq + 4), b1 = load<D4>(chopped_sq + 4),
         b2         = load<D4>(reduced_sq + 4);
      std::size_t i = 0;
      for (; i + 8 <= n; i += 8)
      {
        reduced_norms_body(i, x, g, l, tol, alpha, a0, a1, a2);
        reduced_norms_body(i + 4, x, g, l, tol, alpha, b0, b1, b2);
      }
      if (i + 4 <= n)
      {
        reduced_norms_body(i, x, g, l, tol, alpha, a0, a1, a2);
        i += 4;
      }
      store(free_sq, a0);
      store(chopped_sq, a1);
      store(reduced_sq, a2);
      store(free_sq + 4, b0);
      store(chopped_sq + 4, b1);
      store(reduced_sq + 4, b2);
      for (; i < n; ++i)
      {
        const bool   active = x[i] - l[i] <= tol * (l[i] < 0. ? -l[i] : l[i]);
        const double gm     = 0. < g[i] ? 0. : g[i];
        const double t      = x[i] - alpha * g[i];
        const double m      = l[i] < t ? t : l[i];
        const double red    = g[i] < 0. ? g[i] : (x[i] - m) / alpha;
        free_sq[0] += active ? 0. : g[i] * g[i];
        chopped_sq[0] += active ? gm * gm : 0.;
        reduced_sq[0] += active ? red * red : 0.;
      }
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::max_step(const std::size_t n,
                            const double     *x,
                            const double     *p,
                            const double     *l,
                            RatioLanes       &ratio)
    {
      double(&num)[8] = ratio.num;
      double(&den)[8] = ratio.den;
      std::size_t i   = 0;
      {
        // a second pair of accumulators for the odd blocks of eight
        // (see conjugate_direction)
        D8 a0 = load<D8>(num), a1 = load<D8>(den);
        D8 c0 = {1., 1., 1., 1., 1., 1., 1., 1.}, c1 = {};
        for (; i + 16 <= n; i += 16)
        {
          max_step_body(i, x, p, l, a0, a1);
          max_step_body(i + 8, x, p, l, c0, c1);
        }
        if (i + 8 <= n)
        {
          max_step_body(i, x, p, l, a0, a1);
          i += 8;
        }
        take_smaller(a0, a1, c0, c1);
        store(num, a0);
        store(den, a1);
      }
      if (i + 4 <= n)
      {
        D4 a0 = load<D4>(num), a1 = load<D4>(den);
        max_step_body(i, x, p, l, a0, a1);
        store(num, a0);
        store(den, a1);
        i += 4;
      }
      for (; i < n; ++i)
      {
        const double room = x[i] - l[i];
        const double r    = room < 0. ? 0. : room;
        const bool   take = r * den[0] < num[0] * p[i]; // see take_smaller
        num[0]            = take ? r : num[0];
        den[0]            = take ? p[i] : den[0];
      }
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::feasible_step(const std::size_t n,
                                 double           *x,
                                 const double     *p,
                                 const double     *l,
                                 const double      alpha)
    {
      std::size_t i = 0;
      for (; i + 4 <= n; i += 4)
        feasible_step_body<D4>(i, x, p, l, alpha);
      constexpr double eps8 = 8. * std::numeric_limits<double>::epsilon();
      for (; i < n; ++i)
      {
        const double ap    = alpha * p[i];
        const double y     = x[i] - ap;
        const double scale = (std::abs(y) + std::abs(ap)) + std::abs(l[i]);
        x[i] = (y < l[i] || std::abs(y - l[i]) <= eps8 * scale) ? l[i] : y;
      }
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::projected_step(const std::size_t n,
                                  double           *x,
                                  const double     *g,
                                  const double     *l,
                                  const double      tol,
                                  const double      alpha,
                                  const bool        free_only)
    {
      std::size_t i = 0;
      for (; i + 4 <= n; i += 4)
        projected_step_body<D4>(i, x, g, l, tol, alpha, free_only);
      for (; i < n; ++i)
      {
        const bool   active = free_only && x[i] - l[i] <= tol * std::abs(l[i]);
        const double y      = x[i] - (active ? 0. : alpha * g[i]);
        x[i]                = y < l[i] ? l[i] : y;
      }
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::cost(const std::size_t n,
                        const double     *y,
                        const double     *g,
                        const double     *b,
                        Lanes            &sum_lanes)
    {
      double(&sum)[8] = sum_lanes.v;
      cost_loop<false>(n, y, b, const_cast<double *>(g), sum);
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::residual_cost(const std::size_t n,
                                 const double     *y,
                                 const double     *b,
                                 double           *g,
                                 Lanes            &sum_lanes)
    {
      double(&sum)[8] = sum_lanes.v;
      cost_loop<true>(n, y, b, g, sum);
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::step(const std::size_t n,
                        const double      beta,
                        const double     *d,
                        const double     *Ad,
                        double           *x,
                        double           *g)
    {
      std::size_t i = 0;
      for (; i + 4 <= n; i += 4)
      {
        store(x + i, load<D4>(x + i) + beta * load<D4>(d + i));
        store(g + i, load<D4>(g + i) + beta * load<D4>(Ad + i));
      }
      for (; i < n; ++i)
      {
        x[i] += beta * d[i];
        g[i] += beta * Ad[i];
      }
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::step_differences(const std::size_t n,
                                    const double     *x,
                                    const double     *g,
                                    double           *x_prev,
                                    double           *g_prev,
                                    const bool        copy,
                                    Lanes            &ss_lanes,
                                    Lanes            &sy_lanes)
    {
      double(&ss)[8] = ss_lanes.v;
      double(&sy)[8] = sy_lanes.v;
      D4          a0 = load<D4>(ss), a1 = load<D4>(sy);
      D4          b0 = load<D4>(ss + 4), b1 = load<D4>(sy + 4);
      std::size_t i = 0;
      for (; i + 8 <= n; i += 8)
      {
        differences_body(i, x, g, x_prev, g_prev, copy, a0, a1);
        differences_body(i + 4, x, g, x_prev, g_prev, copy, b0, b1);
      }
      if (i + 4 <= n)
      {
        differences_body(i, x, g, x_prev, g_prev, copy, a0, a1);
        i += 4;
      }
      store(ss, a0);
      store(sy, a1);
      store(ss + 4, b0);
      store(sy + 4, b1);
      for (; i < n; ++i)
      {
        const double si = x[i] - x_prev[i], yi = g[i] - g_prev[i];
        ss[0] += si * si;
        sy[0] += si * yi;
        if (copy)
        {
          x_prev[i] = x[i];
          g_prev[i] = g[i];
        }
      }
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::extrapolate(const std::size_t n,
                               const double      beta,
                               const double     *x,
                               const double     *x_old,
                               const double     *Ax,
                               const double     *Ax_old,
                               const double     *b,
                               double           *g,
                               double           *y,
                               double           *gy)
    {
      const double s = 1. + beta;
      std::size_t  i = 0;
      for (; i + 4 <= n; i += 4)
      {
        const D4 av = load<D4>(Ax + i), bv = load<D4>(b + i);
        store(g + i, av - bv);
        store(y + i, s * load<D4>(x + i) - beta * load<D4>(x_old + i));
        store(gy + i, (s * av - beta * load<D4>(Ax_old + i)) - bv);
      }
      for (; i < n; ++i)
      {
        g[i]  = Ax[i] - b[i];
        y[i]  = s * x[i] - beta * x_old[i];
        gy[i] = (s * Ax[i] - beta * Ax_old[i]) - b[i];
      }
    }


    double
    VectorKernels::min_ratio(const RatioLanes &ratio)
    {
      double value = std::numeric_limits<double>::infinity();
      for (unsigned int j = 0; j < VectorKernels::lanes; ++j)
        if (ratio.den[j] > 0.)
        {
          const double r = ratio.num[j] / ratio.den[j];
          value          = r < value ? r : value;
        }
      return value;
    }


    const char *
    VectorKernels::instruction_set()
    {
#if DUALCONTACT_KERNEL_CLONED
      if (__builtin_cpu_supports("x86-64-v4"))
        return "x86-64-v4";
      if (__builtin_cpu_supports("x86-64-v3"))
        return "x86-64-v3";
#endif
      return "baseline";
    }
  } // namespace qp
} // namespace dualcontact
