/**
 * @file power_iteration.h
 * Estimate of lambda_max(A) for the fixed step alpha_bar = 1.95/lambda_max.
 * Power iteration converges from below, and a step longer than
 * 2/lambda_max makes projection steps increase the cost, hence the safety
 * factor.
 */
#ifndef dualcontact_qp_power_iteration_h
#define dualcontact_qp_power_iteration_h

#include <functional>

namespace dualcontact
{
  namespace qp
  {
    struct PowerIterationResult
    {
      /// safety_factor * estimate: what a solver should use
      double lambda_max = 0.;
      /// the Rayleigh quotient of the last iterate
      double       estimate   = 0.;
      unsigned int iterations = 0;
      /// Hessian products spent
      unsigned int n_products = 0;
    };

    /**
     * Power iteration for the largest eigenvalue of the symmetric positive
     * semidefinite operator @p A.  The start vector depends only on global
     * indices, so the result is the same on any number of ranks.  Stops when
     * the Rayleigh quotient changes by less than @p tolerance (relative) or
     * after @p max_iterations products.  @p layout gives the vector layout.
     */
    template <typename VectorType>
    PowerIterationResult
    power_iteration(
      const std::function<void(VectorType &, const VectorType &)> &A,
      const VectorType                                            &layout,
      unsigned int max_iterations = 100,
      double       tolerance      = 1e-4,
      double       safety_factor  = 1.05);

    /**
     * The same estimate by the Lanczos process: the largest eigenvalue of
     * the tridiagonal matrix T_k of k Lanczos steps (from the same start
     * vector), which approaches lambda_max from below much faster than the
     * power iteration's Rayleigh quotient (it is the best estimate from the
     * Krylov space the power iteration explores, not only from its last
     * vector): on the Delassus matrices of fclib (Hertz exports, 249-501
     * unknowns) 12-15 power products against fewer Lanczos steps for the
     * same tolerance.  No reorthogonalization (the largest Ritz value is
     * unaffected until it has converged).  Stops when the largest Ritz value
     * changes by less than @p tolerance (relative), on an invariant
     * subspace, or after @p max_iterations products; returns safety_factor
     * times it.  The largest eigenvalue of T_k is found by bisection with
     * Sturm sequence counts.
     */
    template <typename VectorType>
    PowerIterationResult
    lanczos_lambda_max(
      const std::function<void(VectorType &, const VectorType &)> &A,
      const VectorType                                            &layout,
      unsigned int max_iterations = 100,
      double       tolerance      = 1e-4,
      double       safety_factor  = 1.05);
  } // namespace qp
} // namespace dualcontact

#endif
