#include <qp/vector_kernels.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

// One clone per instruction set on x86-64 with GCC (the loader's ifunc
// resolver picks one at start-up); elsewhere one portable build of the
// same code.  (DUALCONTACT_KERNEL_NO_CLONES: one build for the compiler's
// -march, to compare the instruction sets' results with the test on one
// machine.)
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
      // Vectors of four and eight doubles, one lane each; comparisons give
      // masks of longs.  GCC lowers a vector wider than the clone's
      // registers to several registers, with the same results.
      typedef double D4 __attribute__((vector_size(32)));
      typedef long   M4 __attribute__((vector_size(32)));
      typedef double D8 __attribute__((vector_size(64)));
      typedef long   M8 __attribute__((vector_size(64)));

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
      // instruction where a blend takes two): the same bits as the
      // selection (+0. where dropped).  The overloads for one double are
      // the scalar code of the last entries.
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

      DUALCONTACT_INLINE double
      keep(const bool mask, const double v)
      {
        return mask ? v : 0.;
      }

      DUALCONTACT_INLINE double
      drop(const bool mask, const double v)
      {
        return mask ? 0. : v;
      }

      // |y| as y < 0 ? -y : y (std::abs)
      template <typename D>
      DUALCONTACT_INLINE D
      absolute(const D y)
      {
        return y < 0. ? -y : y;
      }

      // The loop bodies below are templates on the value type D: a vector
      // of eight or four doubles, or one double for the last entries, so
      // that every entry goes through the same expressions.  These are
      // those of SeparableSet's scalar loops (and of its loops for boxes):
      // std::abs(l) as absolute(l), std::min(g, 0.) as drop(0. < g, g),
      // std::max(r, 0.) as drop(r < 0., r), a selection on the active test
      // as keep / drop.

      /**
       * The lane order of every kernel (see the class documentation): the
       * entries i = 0, 8, 16, ... in vectors over lanes 0-7 (one vector of
       * eight when @p wide, two of four otherwise: lanes 0-3 and 4-7), a
       * remainder of four to seven entries starting with one vector of
       * four on lanes 0-3, then the last one to three entries one at a
       * time on lane 0.  body(i, acc) runs the body at entry i on the
       * accumulators acc[0..K) (vectors, or doubles), which hold the lanes
       * @p lanes[k].  Eight-wide runs faster where the body is long (the
       * CG step), two of four where it is short (a dot product: two
       * independent chains of additions).
       */
      template <bool wide, std::size_t K, typename Body>
      DUALCONTACT_INLINE void
      over_lanes(const std::size_t n,
                 double *const (&lanes)[K],
                 const Body &body)
      {
        std::size_t i = 0;
        if constexpr (wide)
        {
          D8 a[K];
          for (std::size_t k = 0; k < K; ++k)
            a[k] = load<D8>(lanes[k]);
          for (; i + 8 <= n; i += 8)
            body(i, a);
          for (std::size_t k = 0; k < K; ++k)
            store(lanes[k], a[k]);
        }
        else
        {
          D4 a[K], b[K];
          for (std::size_t k = 0; k < K; ++k)
          {
            a[k] = load<D4>(lanes[k]);
            b[k] = load<D4>(lanes[k] + 4);
          }
          for (; i + 8 <= n; i += 8)
          {
            body(i, a);
            body(i + 4, b);
          }
          for (std::size_t k = 0; k < K; ++k)
          {
            store(lanes[k], a[k]);
            store(lanes[k] + 4, b[k]);
          }
        }
        if (i + 4 <= n)
        {
          D4 a[K];
          for (std::size_t k = 0; k < K; ++k)
            a[k] = load<D4>(lanes[k]);
          body(i, a);
          for (std::size_t k = 0; k < K; ++k)
            store(lanes[k], a[k]);
          i += 4;
        }
        for (; i < n; ++i)
        {
          double a[K];
          for (std::size_t k = 0; k < K; ++k)
            a[k] = lanes[k][0];
          body(i, a);
          for (std::size_t k = 0; k < K; ++k)
            lanes[k][0] = a[k];
        }
      }

      // the value type of an accumulator array
      template <typename A>
      using value_of =
        std::remove_reference_t<decltype(std::declval<A &>()[0])>;

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

      /**
       * The two kernels that look for the largest feasible step: with
       * @p wide vectors of eight over lanes 0-7, and a second set of the
       * ratio's accumulators for the odd blocks of eight (its
       * compare-and-blend chain bounds the loop otherwise), merged at the
       * end: the least ratio does not depend on the order, only the choice
       * among equal ones does, the same on every machine.  The sums
       * (acc[0..K), K >= 0, held by lanes[k]) keep the lane order of
       * over_lanes().  body(i, sums, num, den) runs one entry.
       */
      template <std::size_t K, typename Body>
      DUALCONTACT_INLINE void
      over_lanes_with_ratio(const std::size_t    n,
                            double *const *const lanes,
                            double              *num,
                            double              *den,
                            const Body          &body)
      {
        std::size_t i = 0;
        {
          D8 a[K + 1], n0 = load<D8>(num), d0 = load<D8>(den);
          D8 n1 = {1., 1., 1., 1., 1., 1., 1., 1.}, d1 = {};
          for (std::size_t k = 0; k < K; ++k)
            a[k] = load<D8>(lanes[k]);
          for (; i + 16 <= n; i += 16)
          {
            body(i, a, n0, d0);
            body(i + 8, a, n1, d1);
          }
          if (i + 8 <= n)
          {
            body(i, a, n0, d0);
            i += 8;
          }
          take_smaller(n0, d0, n1, d1);
          for (std::size_t k = 0; k < K; ++k)
            store(lanes[k], a[k]);
          store(num, n0);
          store(den, d0);
        }
        if (i + 4 <= n)
        {
          D4 a[K + 1], n0 = load<D4>(num), d0 = load<D4>(den);
          for (std::size_t k = 0; k < K; ++k)
            a[k] = load<D4>(lanes[k]);
          body(i, a, n0, d0);
          for (std::size_t k = 0; k < K; ++k)
            store(lanes[k], a[k]);
          store(num, n0);
          store(den, d0);
          i += 4;
        }
        for (; i < n; ++i)
        {
          double a[K + 1];
          for (std::size_t k = 0; k < K; ++k)
            a[k] = lanes[k][0];
          body(i, a, num[0], den[0]);
          for (std::size_t k = 0; k < K; ++k)
            lanes[k][0] = a[k];
        }
      }

      // whether a bound is active at x: x - l <= tol |l|
      template <typename D>
      DUALCONTACT_INLINE auto
      at_bound(const D xv, const D lv, const double tol)
      {
        return (xv - lv) <= tol * absolute(lv);
      }

      // a bound's squares of the free gradient (g if inactive) and of the
      // chopped gradient (min(g, 0) if active) into s[0], s[1]
      template <typename S, typename M, typename D>
      DUALCONTACT_INLINE void
      add_free_and_chopped(S &s, const M active, const D gv)
      {
        const D gm = drop(0. < gv, gv);
        s[0] += drop(active, gv * gv);
        s[1] += keep(active, gm * gm);
      }

      // The square of the reduced chopped gradient's component of an
      // active bound (thesis 1.4.2) for the step length alpha: g if g < 0,
      // else (x - max(l, x - alpha g)) / alpha, with std::max(l, t) as l <
      // t ? t : l (SeparableSet's sweep)
      template <typename D>
      DUALCONTACT_INLINE D
      reduced_chopped(const D xv, const D gv, const D lv, const double alpha)
      {
        const D t   = xv - alpha * gv;
        const D m   = lv < t ? t : lv;
        const D red = gv < 0. ? gv : (xv - m) / alpha;
        return red * red;
      }

      // The CG step on entry i (x -= alpha p, g -= alpha Ap), and at the
      // new point ||phi||^2, ||beta||^2, phi'Ap into s[0..2], with
      // @p reduced also the reduced chopped gradient's square into s[3]
      template <bool reduced, typename S>
      DUALCONTACT_INLINE void
      cg_step_body(const std::size_t i,
                   double           *x,
                   double           *g,
                   const double     *p,
                   const double     *Ap,
                   const double     *l,
                   const double      tol,
                   const double      alpha,
                   const double      reduced_alpha,
                   S                &s)
      {
        using D    = value_of<S>;
        const D av = load<D>(Ap + i), lv = load<D>(l + i);
        const D xv = load<D>(x + i) - alpha * load<D>(p + i);
        const D gv = load<D>(g + i) - alpha * av;
        store(x + i, xv);
        store(g + i, gv);
        const auto active = at_bound(xv, lv, tol);
        add_free_and_chopped(s, active, gv);
        s[2] += drop(active, gv * av);
        if constexpr (reduced)
          s[3] += keep(active, reduced_chopped(xv, gv, lv, reduced_alpha));
      }

      // elementwise, no sums: body(i) with vectors of four, then doubles
      template <typename Body>
      DUALCONTACT_INLINE void
      elementwise(const std::size_t n, const Body &body)
      {
        std::size_t i = 0;
        for (; i + 4 <= n; i += 4)
          body(i, D4());
        for (; i < n; ++i)
          body(i, 0.);
      }
    } // namespace


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::dots(const std::size_t n,
                        const double     *p,
                        const double     *Ap,
                        const double     *g,
                        Lanes            &pAp,
                        Lanes            &pp,
                        Lanes            &gp)
    {
      over_lanes<false>(
        n,
        {pAp.v, pp.v, gp.v},
        [&](const std::size_t i, auto &s) __attribute__((always_inline)) {
          using D    = value_of<decltype(s)>;
          const D pv = load<D>(p + i), av = load<D>(Ap + i),
                  gv = load<D>(g + i);
          s[0] += pv * av;
          s[1] += pv * pv;
          s[2] += gv * pv;
        });
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::dot(const std::size_t n,
                       const double     *a,
                       const double     *b,
                       Lanes            &ab)
    {
      over_lanes<false>(
        n,
        {ab.v},
        [&](const std::size_t i, auto &s) __attribute__((always_inline)) {
          using D = value_of<decltype(s)>;
          s[0] += load<D>(a + i) * load<D>(b + i);
        });
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
                           Lanes            &free_sq,
                           Lanes            &chopped_sq,
                           Lanes            &phi_Ap)
    {
      over_lanes<true>(
        n,
        {free_sq.v, chopped_sq.v, phi_Ap.v},
        [&](const std::size_t i, auto &s) __attribute__((always_inline)) {
          cg_step_body<false>(i, x, g, p, Ap, l, tol, alpha, 0., s);
        });
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::cg_step_reduced(const std::size_t n,
                                   double           *x,
                                   double           *g,
                                   const double     *p,
                                   const double     *Ap,
                                   const double     *l,
                                   const double      tol,
                                   const double      alpha,
                                   const double      reduced_alpha,
                                   Lanes            &free_sq,
                                   Lanes            &chopped_sq,
                                   Lanes            &phi_Ap,
                                   Lanes            &reduced_sq)
    {
      over_lanes<true>(
        n,
        {free_sq.v, chopped_sq.v, phi_Ap.v, reduced_sq.v},
        [&](const std::size_t i, auto &s) __attribute__((always_inline)) {
          cg_step_body<true>(i, x, g, p, Ap, l, tol, alpha, reduced_alpha, s);
        });
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
                                       Lanes            &pp,
                                       Lanes            &gp,
                                       RatioLanes       &ratio)
    {
      double *const sums[2] = {pp.v, gp.v};
      over_lanes_with_ratio<2>(
        n,
        sums,
        ratio.num,
        ratio.den,
        [&](const std::size_t i, auto &s, auto &num, auto &den)
          __attribute__((always_inline)) {
            using D    = value_of<decltype(s)>;
            const D xv = load<D>(x + i), gv = load<D>(g + i),
                    lv        = load<D>(l + i);
            const D    room   = xv - lv;
            const auto active = at_bound(xv, lv, tol);
            const D    dv     = drop(active, gv) - beta * load<D>(p + i);
            store(p + i, dv);
            s[0] += dv * dv;
            s[1] += gv * dv;
            take_smaller<D>(num, den, drop(room < 0., room), dv);
          });
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::gradient_norms(const std::size_t n,
                                  const double     *x,
                                  const double     *g,
                                  const double     *l,
                                  const double      tol,
                                  double           *phi,
                                  Lanes            &free_sq,
                                  Lanes            &chopped_sq)
    {
      over_lanes<true>(
        n,
        {free_sq.v, chopped_sq.v},
        [&](const std::size_t i, auto &s) __attribute__((always_inline)) {
          using D    = value_of<decltype(s)>;
          const D xv = load<D>(x + i), gv = load<D>(g + i), lv = load<D>(l + i);
          const auto active = at_bound(xv, lv, tol);
          if (phi != nullptr)
            store(phi + i, drop(active, gv));
          add_free_and_chopped(s, active, gv);
        });
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::reduced_norms(const std::size_t n,
                                 const double     *x,
                                 const double     *g,
                                 const double     *l,
                                 const double      tol,
                                 const double      alpha,
                                 Lanes            &free_sq,
                                 Lanes            &chopped_sq,
                                 Lanes            &reduced_sq)
    {
      over_lanes<false>(
        n,
        {free_sq.v, chopped_sq.v, reduced_sq.v},
        [&](const std::size_t i, auto &s) __attribute__((always_inline)) {
          using D    = value_of<decltype(s)>;
          const D xv = load<D>(x + i), gv = load<D>(g + i), lv = load<D>(l + i);
          const auto active = at_bound(xv, lv, tol);
          add_free_and_chopped(s, active, gv);
          s[2] += keep(active, reduced_chopped(xv, gv, lv, alpha));
        });
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::max_step(const std::size_t n,
                            const double     *x,
                            const double     *p,
                            const double     *l,
                            RatioLanes       &ratio)
    {
      over_lanes_with_ratio<0>(
        n,
        nullptr,
        ratio.num,
        ratio.den,
        [&](const std::size_t i, auto &, auto &num, auto &den)
          __attribute__((always_inline)) {
            using D      = std::remove_reference_t<decltype(num)>;
            const D room = load<D>(x + i) - load<D>(l + i);
            take_smaller<D>(num, den, drop(room < 0., room), load<D>(p + i));
          });
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::feasible_step(const std::size_t n,
                                 double           *x,
                                 const double     *p,
                                 const double     *l,
                                 const double      alpha)
    {
      elementwise(
        n, [&](const std::size_t i, auto zero) __attribute__((always_inline)) {
          using D                = decltype(zero);
          constexpr double eps8  = 8. * std::numeric_limits<double>::epsilon();
          const D          lv    = load<D>(l + i);
          const D          ap    = alpha * load<D>(p + i);
          const D          y     = load<D>(x + i) - ap;
          const D          scale = (absolute(y) + absolute(ap)) + absolute(lv);
          // (y < l or snapped) ? l : y, as two selections: GCC
          // 12 turns a selection on the or of two masks into
          // scalar code for AVX-512
          const D below = y < lv ? lv : y;
          store(x + i, absolute(y - lv) <= eps8 * scale ? lv : below);
        });
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
      elementwise(
        n, [&](const std::size_t i, auto zero) __attribute__((always_inline)) {
          using D    = decltype(zero);
          const D xv = load<D>(x + i), lv = load<D>(l + i);
          D       step = alpha * load<D>(g + i);
          if (free_only)
            step = drop(at_bound(xv, lv, tol), step);
          const D y = xv - step;
          store(x + i, y < lv ? lv : y);
        });
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::cost(const std::size_t n,
                        const double     *y,
                        const double     *g,
                        const double     *b,
                        Lanes            &sum)
    {
      over_lanes<false>(
        n,
        {sum.v},
        [&](const std::size_t i, auto &s) __attribute__((always_inline)) {
          using D = value_of<decltype(s)>;
          s[0] += load<D>(y + i) * (load<D>(g + i) - load<D>(b + i));
        });
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::residual_cost(const std::size_t n,
                                 const double     *y,
                                 const double     *b,
                                 double           *g,
                                 Lanes            &sum)
    {
      over_lanes<false>(
        n,
        {sum.v},
        [&](const std::size_t i, auto &s) __attribute__((always_inline)) {
          using D    = value_of<decltype(s)>;
          const D bv = load<D>(b + i);
          const D gv = load<D>(g + i) - bv;
          store(g + i, gv);
          s[0] += load<D>(y + i) * (gv - bv);
        });
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
      elementwise(
        n, [&](const std::size_t i, auto zero) __attribute__((always_inline)) {
          using D = decltype(zero);
          store(x + i, load<D>(x + i) + beta * load<D>(d + i));
          store(g + i, load<D>(g + i) + beta * load<D>(Ad + i));
        });
    }


    DUALCONTACT_KERNEL_CLONES
    void
    VectorKernels::step_differences(const std::size_t n,
                                    const double     *x,
                                    const double     *g,
                                    double           *x_prev,
                                    double           *g_prev,
                                    const bool        copy,
                                    Lanes            &ss,
                                    Lanes            &sy)
    {
      over_lanes<false>(
        n,
        {ss.v, sy.v},
        [&](const std::size_t i, auto &s) __attribute__((always_inline)) {
          using D    = value_of<decltype(s)>;
          const D xv = load<D>(x + i), gv = load<D>(g + i);
          const D sv = xv - load<D>(x_prev + i), yv = gv - load<D>(g_prev + i);
          s[0] += sv * sv;
          s[1] += sv * yv;
          if (copy)
          {
            store(x_prev + i, xv);
            store(g_prev + i, gv);
          }
        });
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
      elementwise(
        n, [&](const std::size_t i, auto zero) __attribute__((always_inline)) {
          using D    = decltype(zero);
          const D av = load<D>(Ax + i), bv = load<D>(b + i);
          store(g + i, av - bv);
          store(y + i, s * load<D>(x + i) - beta * load<D>(x_old + i));
          store(gy + i, (s * av - beta * load<D>(Ax_old + i)) - bv);
        });
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
