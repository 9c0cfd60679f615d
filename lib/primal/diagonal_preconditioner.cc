#include <deal.II/base/exceptions.h>

#include <primal/diagonal_preconditioner.h>

#include <cmath>

namespace dualcontact
{
  namespace primal
  {
    void
    DiagonalPreconditioner::initialize(
      const dealii::SparseMatrix<double> &matrix)
    {
      AssertThrow(matrix.m() == matrix.n(),
                  dealii::ExcMessage("diagonal preconditioner: the matrix "
                                     "is not square"));
      inverse_sqrt_diagonal.reinit(matrix.m());
      for (unsigned int i = 0; i < matrix.m(); ++i)
      {
        const double d = matrix.diag_element(i);
        AssertThrow(d > 0.,
                    dealii::ExcMessage(
                      "diagonal preconditioner: diagonal entry " +
                      std::to_string(i) + " is " + std::to_string(d) +
                      " (the matrix is not positive definite)"));
        inverse_sqrt_diagonal(i) = 1. / std::sqrt(d);
      }
    }


    void
    DiagonalPreconditioner::apply_E_inverse(VectorType       &dst,
                                            const VectorType &src) const
    {
      AssertDimension(src.size(), inverse_sqrt_diagonal.size());
      dst.reinit(src.size(), true);
      for (unsigned int i = 0; i < src.size(); ++i)
        dst(i) = inverse_sqrt_diagonal(i) * src(i);
    }


    void
    DiagonalPreconditioner::apply_E_inverse_transpose(
      VectorType       &dst,
      const VectorType &src) const
    {
      apply_E_inverse(dst, src);
    }


    std::string
    DiagonalPreconditioner::name() const
    {
      return "P-DIAG";
    }
  } // namespace primal
} // namespace dualcontact
