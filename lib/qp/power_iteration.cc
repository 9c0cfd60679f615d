#include <qp/power_iteration.h>
#include <qp/vector_helpers.h>

#include <deal.II/base/exceptions.h>

#include <cmath>
#include <cstdint>

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
      {
        const dealii::IndexSet owned = x.locally_owned_elements();
        double                *v     = x.begin();
        std::size_t            k     = 0;
        for (auto it = owned.begin(); it != owned.end(); ++it, ++k)
          v[k] = start_value(*it);
      }
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


    template PowerIterationResult
    power_iteration<dealii::Vector<double>>(
      const std::function<void(dealii::Vector<double> &,
                               const dealii::Vector<double> &)> &,
      const dealii::Vector<double> &,
      unsigned int,
      double,
      double);
    template PowerIterationResult
    power_iteration<dealii::TrilinosWrappers::MPI::Vector>(
      const std::function<void(dealii::TrilinosWrappers::MPI::Vector &,
                               const dealii::TrilinosWrappers::MPI::Vector &)>
        &,
      const dealii::TrilinosWrappers::MPI::Vector &,
      unsigned int,
      double,
      double);
  } // namespace qp
} // namespace dualcontact
