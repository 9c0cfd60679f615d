/**
 * @file cgc_solver.h
 * CGC (the 1996 report's conjugate projected gradient with facet restarts,
 * cgc.h) as the registered QP solver `cgc` for separable problems of bound
 * and box blocks: the report's DUAL method (section 5.4, table 11.11) on
 * the dual contact problem.
 */
#ifndef dualcontact_qp_cgc_solver_h
#define dualcontact_qp_cgc_solver_h

#include <qp/solver_registry.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * The registry entry `cgc` (bounds and boxes, not chainable): CGC on a
     * Problem whose constraints are bounds and boxes only, each bound
     * x_i >= l a row -x_i <= -l, each box also the row x_i <= u (rows of one
     * entry, which CGC projects on exactly and releases by the report's
     * lemma 7.2, all negative multipliers at once, since such rows are
     * orthogonal).  It uses the shared parameters Tolerance, Maximum
     * iterations and Stagnation window of `QP solver' and CGC's defaults
     * otherwise (remark 7.3's loose first facets included); it refuses
     * curved blocks, equality constraints (SMALSE-M wraps it as any other
     * solver) and stopping criteria other than `projected'.  Its
     * statistics are CGC's (cgc.h) with the KKT residuals of the separable
     * problem.  The solver class is private to cgc_solver.cc: a program
     * reaches it by name (create<V>("cgc", parameters)).
     */
    SolverEntry
    cgc_solver_entry();
  } // namespace qp
} // namespace dualcontact

#endif
