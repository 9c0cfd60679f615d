#pragma once

#include <primal/lower_triangular.h>
#include <primal/preconditioner.h>

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
    class SSORPreconditioner : public Preconditioner
    {
    public:
      explicit SSORPreconditioner(const double omega = 1.);

      void
      initialize(const dealii::SparseMatrix<double> &matrix) override;
      void
      apply_E_inverse(VectorType &dst, const VectorType &src) const override;
      void
      apply_E_inverse_transpose(VectorType       &dst,
                                const VectorType &src) const override;
      std::string
      name() const override;

      /** The factor E. */
      const LowerTriangular &
      factor() const;

    private:
      double          omega;
      LowerTriangular E;
    };
  } // namespace primal
} // namespace dualcontact
