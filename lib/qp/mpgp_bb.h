/**
 * @file mpgp_bb.h
 * MPGP-BB (thesis 2.4.2): MPGP whose projection steps use the Barzilai-Borwein
 * length s's/s'As; a step whose cost exceeds the largest cost before the last
 * `MPGP-BB/Memory' BB steps is redone with alpha_bar (a fall-back): a
 * non-monotone safeguard (Grippo-Lampariello-Lucidi) that the thesis leaves
 * out; memory 0 makes it monotone.
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
     * Barzilai-Borwein length s's/s'As, with the non-monotone safeguard
     * described above.  Parameters: Gamma, Alpha bar factor, its own
     * MPGPBBParameters (SolverParameters::mpgp_bb, `subsection MPGP-BB`),
     * and the common ones of SolverParameters.
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
