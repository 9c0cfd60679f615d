/**
 * @file kkt_residuals.h
 * KKT residuals of a candidate solution, the same for every solver, so
 * that any correct solver produces the same report (cf. PermonQP).
 */
#ifndef dualcontact_qp_kkt_residuals_h
#define dualcontact_qp_kkt_residuals_h

#include <qp/problem.h>
#include <qp/solver_statistics.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * Absolute KKT residuals of @p x for @p problem (one Hessian product,
     * not counted anywhere):
     *  - stationarity: ||g^P(P(x))|| with g = A x - b (minus B'nu for the
     *    least-squares nu when equality constraints are given -- not yet:
     *    with equalities this is ||g^P|| of the plain gradient, callers
     *    such as SMALSE-M overwrite it with their own Lagrangian gradient);
     *  - feasibility: ||x - P(x)|| (+ ||Bx - c|| with equalities);
     *  - complementarity: SeparableSet::complementarity() at x.
     */
    template <typename VectorType>
    KKTResiduals
    compute_kkt_residuals(const Problem<VectorType> &problem,
                          const VectorType          &x);
  } // namespace qp
} // namespace dualcontact

#endif
