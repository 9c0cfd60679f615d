/**
 * @file cgc_solver.h
 * CGC (the 1996 report's conjugate projected gradient with facet restarts,
 * cgc.h) as a registered QP solver for separable problems of bound and box
 * blocks: the report's DUAL method (section 5.4, table 11.1) on the dual
 * contact problem.
 */
#ifndef dualcontact_qp_cgc_solver_h
#define dualcontact_qp_cgc_solver_h

#include <qp/solver_base.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * CGC on a Problem whose constraints are bounds and boxes only: each
     * bound x_i >= l a row -x_i <= -l, each box also the row x_i <= u
     * (rows of one entry, which CGC projects on exactly and releases by the
     * report's rule: all negative multipliers at once, lemma 7.2, since
     * such rows are orthogonal).  Uses the shared parameters Tolerance,
     * Maximum iterations and Stagnation window of `QP solver' and CGC's
     * defaults otherwise (remark 7.3's loose first facets included).
     * Refuses equality constraints and curved blocks.  The statistics are
     * CGC's (cgc.h), with the KKT residuals of the separable problem.
     */
    template <typename VectorType>
    class CGCSolver : public SolverBase<VectorType>
    {
    public:
      explicit CGCSolver(const SolverParameters &parameters);

      SolverStatistics
      solve(const Problem<VectorType> &problem, VectorType &x) override;
    };
  } // namespace qp
} // namespace dualcontact

#endif
