/**
 * @file mwpgp.h
 * MwPGP (thesis 2.4.3): MPGP with the weak proportioning test 2 delta
 * ||g~^P_alpha||^2 <= ||phi||^2 on the reduced projected gradient, for strongly
 * curved sets (ill-conditioned ellipses).
 */
#ifndef dualcontact_qp_mwpgp_h
#define dualcontact_qp_mwpgp_h

#include <qp/active_set_solver.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * MwPGP (thesis 2.4.3): MPGP with the weak proportioning test 2 delta
     * ||g~^P_alpha||^2 <= ||phi||^2 on the reduced projected gradient, for
     * strongly curved sets (ill-conditioned ellipses). Parameters: its own
     * MwPGPParameters (SolverParameters::mwpgp, `subsection MwPGP`: Delta),
     * Alpha bar factor, and the common ones of SolverParameters.
     */
    template <typename VectorType>
    class MwPGP : public ActiveSetSolver<VectorType>
    {
    public:
      explicit MwPGP(const SolverParameters &parameters);

      /// the variant this solver runs
      static ActiveSetVariant
      variant();
    };
  } // namespace qp
} // namespace dualcontact

#endif
