#pragma once

#include <primal/preconditioner.h>

namespace dualcontact
{
  namespace primal
  {
    /**
     * W = D, the diagonal of C; E = D^{1/2} (report, section 10: "it is
     * sufficient to store only the vector").
     */
    class DiagonalPreconditioner : public Preconditioner
    {
    public:
      void
      initialize(const dealii::SparseMatrix<double> &matrix) override;
      void
      apply_E_inverse(VectorType &dst, const VectorType &src) const override;
      void
      apply_E_inverse_transpose(VectorType       &dst,
                                const VectorType &src) const override;
      std::string
      name() const override;

    private:
      /** 1 / sqrt(c_ii) */
      VectorType inverse_sqrt_diagonal;
    };
  } // namespace primal
} // namespace dualcontact
