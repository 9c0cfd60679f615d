/**
 * @file mprgp.h
 * MPRGP (thesis 2.4.4) with the solvability test of MPRGPS (2.4.5): bound and
 * box constraints only; the non-proportional step is a steepest-descent step
 * along the chopped gradient, the expansion after a half-step uses the free
 * gradient.
 */
#ifndef dualcontact_qp_mprgp_h
#define dualcontact_qp_mprgp_h

#include <qp/active_set_solver.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * MPRGP (thesis 2.4.4) with the solvability test of MPRGPS (2.4.5): bound
     * and box constraints only; the non-proportional step is a steepest-descent
     * step along the chopped gradient, the expansion after a half-step uses the
     * free gradient. Parameters: Gamma, Alpha bar factor, and the
     * common ones of SolverParameters.
     */
    template <typename VectorType>
    class MPRGP : public ActiveSetSolver<VectorType>
    {
    public:
      explicit MPRGP(const SolverParameters &parameters);

      /// the variant this solver runs
      static ActiveSetVariant
      variant();
    };
  } // namespace qp
} // namespace dualcontact

#endif
