/**
 * @file apgd.h
 * APGD, Nesterov's accelerated projected gradient descent (thesis 2.3,
 * algorithm 6).  Own parameters: APGDParameters (SolverParameters::apgd,
 * `subsection QP solver/APGD`: L factor).
 */
#ifndef dualcontact_qp_apgd_h
#define dualcontact_qp_apgd_h

#include <qp/solver_base.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * @ref APGD: see the class documentation in apgd.cc's header comment
     * below for the algorithm and its parameters.
     */
    template <typename VectorType>
    class APGD : public SolverBase<VectorType>
    {
    public:
      explicit APGD(const SolverParameters &parameters);

      SolverStatistics
      solve(const Problem<VectorType> &problem, VectorType &x) override;
    };
  } // namespace qp
} // namespace dualcontact

#endif
