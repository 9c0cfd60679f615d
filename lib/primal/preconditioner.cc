#include <deal.II/base/exceptions.h>

#include <primal/complete_cholesky.h>
#include <primal/diagonal_preconditioner.h>
#include <primal/incomplete_cholesky.h>
#include <primal/preconditioner.h>
#include <primal/ssor_preconditioner.h>

namespace dualcontact
{
  namespace primal
  {
    void
    Preconditioner::apply_inverse(VectorType &dst, const VectorType &src) const
    {
      VectorType tmp(src.size());
      apply_E_inverse(tmp, src);
      apply_E_inverse_transpose(dst, tmp);
    }


    std::unique_ptr<Preconditioner>
    Preconditioner::create(const std::string &type, const double omega)
    {
      if (type == "none")
        return nullptr;
      if (type == "diagonal")
        return std::make_unique<DiagonalPreconditioner>();
      if (type == "ssor")
        return std::make_unique<SSORPreconditioner>(omega);
      if (type == "ic")
        return std::make_unique<IncompleteCholesky>(false);
      if (type == "icd")
        return std::make_unique<IncompleteCholesky>(true);
      if (type == "cholesky")
        return std::make_unique<CompleteCholesky>();
      AssertThrow(false,
                  dealii::ExcMessage("Unknown preconditioner `" + type +
                                     "' (none, diagonal, ssor, ic, icd, "
                                     "cholesky)."));
      return nullptr;
    }
  } // namespace primal
} // namespace dualcontact
