/**
 * @file pbbf.h
 * PBBf, projected Barzilai-Borwein with fall-back (thesis 2.2, algorithm 5).
 * Own parameters: PBBfParameters (SolverParameters::pbbf, `subsection QP
 * solver/PBBf`: K).
 */
#ifndef dualcontact_qp_pbbf_h
#define dualcontact_qp_pbbf_h

#include <qp/solver_base.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * @ref PBBf: see the class documentation in pbbf.cc's header comment
     * below for the algorithm and its parameters.
     */
    template <typename VectorType>
    class PBBf : public SolverBase<VectorType>
    {
    public:
      explicit PBBf(const SolverParameters &parameters);

      SolverStatistics
      solve(const Problem<VectorType> &problem, VectorType &x) override;
    };
  } // namespace qp
} // namespace dualcontact

#endif
