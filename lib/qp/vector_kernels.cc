#include <qp/vector_kernels.h>

#include <cstring>
#include <limits>

// One clone per instruction set on x86-64 with GCC (the loader's ifunc
// resolver picks one at start-up); elsewhere one portable build of the
// same code.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#  define DUALCONTACT_KERNEL_CLONES \
    __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#  define DUALCONTACT_KERNEL_CLONED 1
#else
#  define DUALCONTACT_KERNEL_CLONES
#  define DUALCONTACT_KERNEL_CLONED 0
#endif

#define DUALCONTACT_INLINE inline __attribute__((always_inline))

namespace dualcontact
{
  namespace qp
  {
    namespace vector_kernels_impl
    {
      // four doubles, one lane each; comparisons give a mask of longs
      typedef double v4d __attribute__((vector_size(32)));

      DUALCONTACT_INLINE v4d
      load(const double *a)
      {
        v4d r;
        std::memcpy(&r, a, sizeof(r));
        return r;
      }

      DUALCONTACT_INLINE void
      store(double *a, const v4d v)
      {
        std::memcpy(a, &v, sizeof(v));
      }

      DUALCONTACT_INLINE v4d
      load_lanes(const double (&a)[4])
      {
        return load(a);
      }

      DUALCONTACT_INLINE void
      store_lanes(double (&a)[4], const v4d v)
      {
        store(a, v);
      }

      // The expressions below are those of the scalar loops (and of the
      // remainder loops here), written for four lanes: std::abs(l) as
      // l < 0 ? -l : l, std::min(g, 0.) as 0. < g ? 0. : g, std::max(r,
      // 0.) as r < 0. ? 0. : r.

      DUALCONTACT_KERNEL_CLONES void
      dots(const std::size_t n,
           const double     *p,
           const double     *Ap,
           const double     *g,
           double (&pAp)[4],
           double (&pp)[4],
           double (&gp)[4])
      {
        v4d               s0 = load_lanes(pAp), s1 = load_lanes(pp),
            s2               = load_lanes(gp);
        const std::size_t m  = n - n % 4;
        for (std::size_t i = 0; i < m; i += 4)
        {
          const v4d pv = load(p + i), av = load(Ap + i), gv = load(g + i);
          s0 += pv * av;
          s1 += pv * pv;
          s2 += gv * pv;
        }
        store_lanes(pAp, s0);
        store_lanes(pp, s1);
        store_lanes(gp, s2);
        for (std::size_t i = m; i < n; ++i)
        {
          pAp[0] += p[i] * Ap[i];
          pp[0] += p[i] * p[i];
          gp[0] += g[i] * p[i];
        }
      }

      DUALCONTACT_KERNEL_CLONES void
      dot(const std::size_t n,
          const double     *a,
          const double     *b,
          double (&ab)[4])
      {
        v4d               s0 = load_lanes(ab);
        const std::size_t m  = n - n % 4;
        for (std::size_t i = 0; i < m; i += 4)
          s0 += load(a + i) * load(b + i);
        store_lanes(ab, s0);
        for (std::size_t i = m; i < n; ++i)
          ab[0] += a[i] * b[i];
      }

      DUALCONTACT_KERNEL_CLONES void
      cg_step(const std::size_t n,
              double           *x,
              double           *g,
              const double     *p,
              const double     *Ap,
              const double     *l,
              const double      tol,
              const double      alpha,
              double (&free_sq)[4],
              double (&chopped_sq)[4],
              double (&phi_Ap)[4])
      {
        v4d fs = load_lanes(free_sq), bs = load_lanes(chopped_sq),
            pa                = load_lanes(phi_Ap);
        const v4d         zero = {0., 0., 0., 0.};
        const std::size_t m    = n - n % 4;
        for (std::size_t i = 0; i < m; i += 4)
        {
          const v4d av = load(Ap + i), lv = load(l + i);
          const v4d xv = load(x + i) - alpha * load(p + i);
          const v4d gv = load(g + i) - alpha * av;
          store(x + i, xv);
          store(g + i, gv);
          const auto active = (xv - lv) <= tol * (lv < 0. ? -lv : lv);
          const v4d  gm     = 0. < gv ? zero : gv;
          fs += active ? zero : gv * gv;
          bs += active ? gm * gm : zero;
          pa += active ? zero : gv * av;
        }
        store_lanes(free_sq, fs);
        store_lanes(chopped_sq, bs);
        store_lanes(phi_Ap, pa);
        for (std::size_t i = m; i < n; ++i)
        {
          x[i] -= alpha * p[i];
          g[i] -= alpha * Ap[i];
          const bool active =
            x[i] - l[i] <= tol * (l[i] < 0. ? -l[i] : l[i]);
          const double gm = 0. < g[i] ? 0. : g[i];
          free_sq[0] += active ? 0. : g[i] * g[i];
          chopped_sq[0] += active ? gm * gm : 0.;
          phi_Ap[0] += active ? 0. : g[i] * Ap[i];
        }
      }

      DUALCONTACT_KERNEL_CLONES void
      conjugate_direction(const std::size_t n,
                          const double     *x,
                          const double     *g,
                          const double     *l,
                          const double      tol,
                          const double      beta,
                          double           *p,
                          double (&pp)[4],
                          double (&gp)[4],
                          double (&num)[4],
                          double (&den)[4])
      {
        v4d s0 = load_lanes(pp), s1 = load_lanes(gp), nu = load_lanes(num),
            de                = load_lanes(den);
        const v4d         zero = {0., 0., 0., 0.};
        const std::size_t m    = n - n % 4;
        for (std::size_t i = 0; i < m; i += 4)
        {
          const v4d  xv = load(x + i), gv = load(g + i), lv = load(l + i);
          const v4d  room   = xv - lv;
          const auto active = room <= tol * (lv < 0. ? -lv : lv);
          const v4d  dv     = (active ? zero : gv) - beta * load(p + i);
          store(p + i, dv);
          s0 += dv * dv;
          s1 += gv * dv;
          const v4d  r    = room < 0. ? zero : room;
          const auto take = (dv > 0.) & (r * de < nu * dv);
          nu              = take ? r : nu;
          de              = take ? dv : de;
        }
        store_lanes(pp, s0);
        store_lanes(gp, s1);
        store_lanes(num, nu);
        store_lanes(den, de);
        for (std::size_t i = m; i < n; ++i)
        {
          const double room   = x[i] - l[i];
          const bool   active = room <= tol * (l[i] < 0. ? -l[i] : l[i]);
          const double di     = (active ? 0. : g[i]) - beta * p[i];
          p[i]                = di;
          pp[0] += di * di;
          gp[0] += g[i] * di;
          const double r    = room < 0. ? 0. : room;
          const bool   take = di > 0. && r * den[0] < num[0] * di;
          num[0]            = take ? r : num[0];
          den[0]            = take ? di : den[0];
        }
      }
    } // namespace vector_kernels_impl


    void
    VectorKernels::dots(const std::size_t n,
                       const double     *p,
                       const double     *Ap,
                       const double     *g,
                       Lanes            &pAp,
                       Lanes            &pp,
                       Lanes            &gp)
    {
      vector_kernels_impl::dots(n, p, Ap, g, pAp.v, pp.v, gp.v);
    }


    void
    VectorKernels::dot(const std::size_t n,
                       const double     *a,
                       const double     *b,
                       Lanes            &ab)
    {
      vector_kernels_impl::dot(n, a, b, ab.v);
    }


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
      vector_kernels_impl::cg_step(
        n, x, g, p, Ap, l, tol, alpha, free_sq.v, chopped_sq.v, phi_Ap.v);
    }


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
      vector_kernels_impl::conjugate_direction(
        n, x, g, l, tol, beta, p, pp.v, gp.v, ratio.num, ratio.den);
    }


    double
    VectorKernels::min_ratio(const RatioLanes &ratio)
    {
      double value = std::numeric_limits<double>::infinity();
      for (unsigned int j = 0; j < 4; ++j)
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
