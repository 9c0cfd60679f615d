#pragma once

#include <primal/triangular_factor_preconditioner.h>

namespace dualcontact
{
  namespace primal
  {
    /**
     * SSOR (report, section 10, eq. 10.1): with C = D + L + L',
     *   W = (D/omega + L) (D/omega)^{-1} (D/omega + L)',
     *   E = (D/omega + L) (D/omega)^{-1/2},
     * omega in (0, 2); the factor 1/(2 - omega) of W is omitted (it scales
     * W, which changes neither version's iterates).  The report found that
     * omega != 1 changed little with constraints present.
     */
    class SSORPreconditioner : public TriangularFactorPreconditioner
    {
    public:
      explicit SSORPreconditioner(const double omega = 1.);

      void
      initialize(const dealii::SparseMatrix<double> &matrix) override;
      std::string
      name() const override;

    private:
      double omega;
    };
  } // namespace primal
} // namespace dualcontact
