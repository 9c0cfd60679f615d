#include <qp/power_iteration.h>
#include <qp/vector_helpers.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dualcontact
{
  namespace qp
  {
    namespace
    {
      // A deterministic pseudo-random value in [0.5, 1.5) for a global
      // index: positive everywhere so that the start vector is not
      // orthogonal to the Perron vector of an elementwise-positive A, and
      // irregular so it is unlikely to be orthogonal to any eigenvector.
      double
      start_value(std::uint64_t i)
      {
        i += 0x9e3779b97f4a7c15ULL;
        i = (i ^ (i >> 30)) * 0xbf58476d1ce4e5b9ULL;
        i = (i ^ (i >> 27)) * 0x94d049bb133111ebULL;
        i = i ^ (i >> 31);
        return 0.5 + static_cast<double>(i >> 11) / 9007199254740992.;
      }

      template <typename VectorType>
      void
      fill_start(VectorType &x)
      {
        const dealii::IndexSet owned = x.locally_owned_elements();
        double                *v     = x.begin();
        std::size_t            k     = 0;
        for (auto it = owned.begin(); it != owned.end(); ++it, ++k)
          v[k] = start_value(*it);
      }

      // Largest eigenvalue of the symmetric tridiagonal matrix with
      // diagonal a and off-diagonal b (b.size() == a.size() - 1):
      // bisection on the Sturm count (number of eigenvalues below s)
      // inside the Gershgorin interval
      double
      largest_tridiagonal_eigenvalue(const std::vector<double> &a,
                                     const std::vector<double> &b)
      {
        const std::size_t n  = a.size();
        double            lo = a[0], hi = a[0];
        for (std::size_t i = 0; i < n; ++i)
        {
          const double r = (i > 0 ? std::abs(b[i - 1]) : 0.) +
                           (i + 1 < n ? std::abs(b[i]) : 0.);
          lo = std::min(lo, a[i] - r);
          hi = std::max(hi, a[i] + r);
        }
        const auto below = [&](const double s)
        {
          unsigned int count = 0;
          double       d     = 1.;
          for (std::size_t i = 0; i < n; ++i)
          {
            const double bb = i > 0 ? b[i - 1] * b[i - 1] : 0.;
            d               = a[i] - s - (i > 0 ? bb / d : 0.);
            if (d == 0.)
              d = -1e-300; // s is an eigenvalue: count it as below
            count += d < 0.;
          }
          return count;
        };
        // the largest eigenvalue: the smallest s with n eigenvalues below
        for (int it = 0; it < 200 && hi - lo > 1e-15 * std::abs(hi); ++it)
        {
          const double mid = 0.5 * (lo + hi);
          if (below(mid) >= n)
            hi = mid;
          else
            lo = mid;
        }
        return hi;
      }
    } // namespace


    template <typename VectorType>
    PowerIterationResult
    power_iteration(
      const std::function<void(VectorType &, const VectorType &)> &A,
      const VectorType                                            &layout,
      const unsigned int max_iterations,
      const double       tolerance,
      const double       safety_factor)
    {
      AssertThrow(max_iterations >= 1,
                  dealii::ExcMessage("power iteration: need >= 1 iteration"));
      AssertThrow(safety_factor >= 1.,
                  dealii::ExcMessage(
                    "power iteration: the safety factor must be >= 1"));
      PowerIterationResult result;
      VectorType           x(layout), y(layout);
      fill_start(x);
      const double norm0 = internal::norm(x);
      if (norm0 == 0.) // empty problem
        return result;
      x /= norm0;
      double estimate = 0.;
      for (unsigned int it = 0; it < max_iterations; ++it)
      {
        A(y, x);
        ++result.n_products;
        const double rayleigh = internal::dot(x, y); // x has unit norm
        const double norm_y   = internal::norm(y);
        AssertThrow(std::isfinite(norm_y),
                    dealii::ExcMessage(
                      "power iteration: non-finite Hessian product"));
        result.iterations     = it + 1;
        const double previous = estimate;
        estimate              = rayleigh;
        if (norm_y == 0.) // A x = 0: x in the kernel; A may still be 0
          break;
        x.equ(1. / norm_y, y);
        if (it > 0 &&
            std::abs(estimate - previous) <= tolerance * std::abs(estimate))
          break;
      }
      result.estimate = estimate;
      // A = 0 (or x in its kernel): any positive number is a safe bound for
      // step lengths; callers see estimate == 0 and can tell.
      result.lambda_max = estimate > 0. ? safety_factor * estimate : 1.;
      return result;
    }


    template <typename VectorType>
    PowerIterationResult
    lanczos_lambda_max(
      const std::function<void(VectorType &, const VectorType &)> &A,
      const VectorType                                            &layout,
      const unsigned int max_iterations,
      const double       tolerance,
      const double       safety_factor)
    {
      AssertThrow(max_iterations >= 1,
                  dealii::ExcMessage("Lanczos: need >= 1 iteration"));
      AssertThrow(safety_factor >= 1.,
                  dealii::ExcMessage(
                    "Lanczos: the safety factor must be >= 1"));
      PowerIterationResult result;
      VectorType           v(layout), w(layout), v_previous(layout);
      fill_start(v);
      const double norm0 = internal::norm(v);
      if (norm0 == 0.) // empty problem
        return result;
      v /= norm0;
      v_previous = 0.;
      std::vector<double> alpha, beta;
      double              estimate = 0.;
      for (unsigned int it = 0; it < max_iterations; ++it)
      {
        A(w, v);
        ++result.n_products;
        const double a = internal::dot(v, w);
        AssertThrow(std::isfinite(a),
                    dealii::ExcMessage("Lanczos: non-finite Hessian product"));
        alpha.push_back(a);
        // w -= a v + beta_{k-1} v_{k-1}
        w.add(-a, v);
        if (!beta.empty())
          w.add(-beta.back(), v_previous);
        const double b        = internal::norm(w);
        const double previous = estimate;
        estimate              = largest_tridiagonal_eigenvalue(alpha, beta);
        result.iterations     = it + 1;
        if ((it > 0 &&
             std::abs(estimate - previous) <= tolerance * std::abs(estimate)) ||
            b <= 1e-14 * std::abs(estimate) || b == 0.)
          break;
        beta.push_back(b);
        v_previous.swap(v);
        v.equ(1. / b, w);
      }
      result.estimate   = estimate;
      result.lambda_max = estimate > 0. ? safety_factor * estimate : 1.;
      return result;
    }


#define DUALCONTACT_INSTANTIATE_POWER_ITERATION(VectorType)        \
  template PowerIterationResult power_iteration<VectorType>(       \
    const std::function<void(VectorType &, const VectorType &)> &, \
    const VectorType &,                                            \
    unsigned int,                                                  \
    double,                                                        \
    double);                                                       \
  template PowerIterationResult lanczos_lambda_max<VectorType>(    \
    const std::function<void(VectorType &, const VectorType &)> &, \
    const VectorType &,                                            \
    unsigned int,                                                  \
    double,                                                        \
    double);

    DUALCONTACT_INSTANTIATE_POWER_ITERATION(dealii::Vector<double>)
    DUALCONTACT_INSTANTIATE_POWER_ITERATION(
      dealii::TrilinosWrappers::MPI::Vector)
#undef DUALCONTACT_INSTANTIATE_POWER_ITERATION
  } // namespace qp
} // namespace dualcontact
