/**
 * @file mpgp.h
 * MPGP (thesis 2.4.1, algorithm 7): any separable set; gradient projection
 * steps with the fixed length alpha_bar.
 */
#ifndef dualcontact_qp_mpgp_h
#define dualcontact_qp_mpgp_h

#include <qp/active_set_solver.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * MPGP (thesis 2.4.1, algorithm 7): any separable set; gradient projection
     * steps with the fixed length alpha_bar. Parameters: Gamma, Alpha bar
     * factor, and the common ones of SolverParameters.
     */
    template <typename VectorType>
    class MPGP : public ActiveSetSolver<VectorType>
    {
    public:
      explicit MPGP(const SolverParameters &parameters);

      /// the variant this solver runs
      static ActiveSetVariant
      variant();
    };
  } // namespace qp
} // namespace dualcontact

#endif
