#include <primal/triangular_factor_preconditioner.h>

namespace dualcontact
{
  namespace primal
  {
    void
    TriangularFactorPreconditioner::apply_E_inverse(VectorType       &dst,
                                                    const VectorType &src) const
    {
      dst = src;
      E.solve(dst);
    }


    void
    TriangularFactorPreconditioner::apply_E_inverse_transpose(
      VectorType       &dst,
      const VectorType &src) const
    {
      dst = src;
      E.solve_transpose(dst);
    }


    const LowerTriangular &
    TriangularFactorPreconditioner::factor() const
    {
      return E;
    }
  } // namespace primal
} // namespace dualcontact
