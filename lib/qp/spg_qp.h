/**
 * @file spg_qp.h
 * SPG-QP, the spectral projected gradient method for QP (thesis 2.1.4,
 * algorithm 4).  Own parameters: SPGQPParameters (SolverParameters::spg,
 * `subsection QP solver/SPG-QP`: m, gamma, sigma2, alpha0 factor).
 */
#ifndef dualcontact_qp_spg_qp_h
#define dualcontact_qp_spg_qp_h

#include <qp/solver_base.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * @ref SPGQP: see the class documentation in spg_qp.cc's header comment
     * below for the algorithm and its parameters.
     */
    template <typename VectorType>
    class SPGQP : public SolverBase<VectorType>
    {
    public:
      explicit SPGQP(const SolverParameters &parameters);

      SolverStatistics
      solve(const Problem<VectorType> &problem, VectorType &x) override;
    };
  } // namespace qp
} // namespace dualcontact

#endif
