/**
 * @file mpgp_bb.h
 * MPGP-BB (thesis 2.4.2): MPGP whose projection steps use the Barzilai-Borwein
 * length s's/s'As; a step that increases the cost is redone with alpha_bar
 * (counted as fall-back), which keeps the method monotone.
 */
#ifndef dualcontact_qp_mpgp_bb_h
#define dualcontact_qp_mpgp_bb_h

#include <qp/active_set_solver.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * MPGP-BB (thesis 2.4.2): MPGP whose projection steps use the
     * Barzilai-Borwein length s's/s'As; a step that increases the cost is
     * redone with alpha_bar (counted as fall-back), which keeps the method
     * monotone. Parameters: Gamma / MwPGP delta, Alpha bar factor, and the
     * common ones of SolverParameters.
     */
    template <typename VectorType>
    class MPGPBB : public ActiveSetSolver<VectorType>
    {
    public:
      explicit MPGPBB(const SolverParameters &parameters);

      /// the variant this solver runs
      static ActiveSetVariant
      variant();
    };
  } // namespace qp
} // namespace dualcontact

#endif
