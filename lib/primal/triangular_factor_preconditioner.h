#pragma once

#include <primal/lower_triangular.h>
#include <primal/preconditioner.h>

namespace dualcontact
{
  namespace primal
  {
    /**
     * A preconditioner W = E E' whose factor E is one sparse lower
     * triangular matrix held by the preconditioner itself (the report's
     * section 10: SSOR and the incomplete Cholesky variants).  Applying
     * E^{-1} and E^{-T} is then the same forward / backward substitution
     * for all of them; the derived classes only compute E in initialize().
     * (The complete Cholesky factor lives inside CHOLMOD, with its
     * permutation, and is applied there instead.)
     */
    class TriangularFactorPreconditioner : public Preconditioner
    {
    public:
      /** dst = E^{-1} src by forward substitution. */
      void
      apply_E_inverse(VectorType &dst, const VectorType &src) const override;
      /** dst = E^{-T} src by backward substitution. */
      void
      apply_E_inverse_transpose(VectorType       &dst,
                                const VectorType &src) const override;

      /** The factor E. */
      const LowerTriangular &
      factor() const;

    protected:
      /** Set by initialize() of the derived class. */
      LowerTriangular E;
    };
  } // namespace primal
} // namespace dualcontact
