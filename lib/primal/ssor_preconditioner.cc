#include <deal.II/base/exceptions.h>

#include <primal/ssor_preconditioner.h>

#include <cmath>

namespace dualcontact
{
  namespace primal
  {
    SSORPreconditioner::SSORPreconditioner(const double omega)
        : omega(omega)
    {
      AssertThrow(omega > 0. && omega < 2.,
                  dealii::ExcMessage("SSOR relaxation parameter omega must "
                                     "lie in (0, 2), got " +
                                     std::to_string(omega)));
    }


    void
    SSORPreconditioner::initialize(const dealii::SparseMatrix<double> &matrix)
    {
      E.copy_lower_part(matrix);
      for (unsigned int j = 0; j < E.size(); ++j)
      {
        const double d = E.diagonal[j];
        AssertThrow(d > 0.,
                    dealii::ExcMessage(
                      "SSOR preconditioner: diagonal entry " +
                      std::to_string(j) + " is " + std::to_string(d) +
                      " (the matrix is not positive definite)"));
        // column j of (D/omega + L) (D/omega)^{-1/2}
        const double scale = 1. / std::sqrt(d / omega);
        E.diagonal[j]      = std::sqrt(d / omega);
        for (std::size_t k = E.column_start[j]; k < E.column_start[j + 1]; ++k)
          E.values[k] *= scale;
      }
    }


    std::string
    SSORPreconditioner::name() const
    {
      return "P-SOR";
    }
  } // namespace primal
} // namespace dualcontact
