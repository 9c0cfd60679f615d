#pragma once

#include <primal/triangular_factor_preconditioner.h>

namespace dualcontact
{
  namespace primal
  {
    /**
     * Incomplete Cholesky factorization W = E E' on the pattern of C
     * (report, section 10): Gaussian elimination that keeps only the
     * entries of L where C has non-zeros (P-ILL), or, with diagonal
     * compensation, adds every dropped update to the diagonal of its row
     * (P-ILLD, "modified" incomplete Cholesky), so that W has the row sums
     * of C: W 1 = C 1.
     *
     * The elimination is right-looking, as in the report: at step r the
     * pivot c_rr, l_ir = c_ir / c_rr, and c_ij -= l_ir c_rj for i >= j > r
     * in the pattern; an update at (i, j) outside the pattern is dropped
     * (or, compensated, added to c_ii and, by symmetry, c_jj).  E = L
     * D^{1/2} with the unit lower L and the pivots D.
     *
     * Stability is guaranteed only for diagonally dominant M-matrices
     * (report, theorem 10.2); an elasticity stiffness matrix is not one.  If
     * a pivot is not positive (below 1e-12 of the diagonal entry it came
     * from), the factorization is restarted on C + alpha diag(C) with alpha
     * = 1e-3, 2e-3, 4e-3, ... (at most 30 times); shift() tells which
     * alpha was used (0 on the bridge and the tests).
     */
    class IncompleteCholesky : public TriangularFactorPreconditioner
    {
    public:
      explicit IncompleteCholesky(const bool diagonal_compensation);

      void
      initialize(const dealii::SparseMatrix<double> &matrix) override;
      std::string
      name() const override;
      /** The diagonal shift alpha the factorization needed (0: none). */
      double
      shift() const;

    private:
      /** One attempt on C + alpha diag(C); false at a non-positive pivot. */
      bool
      factorize(const LowerTriangular &lower, const double alpha);

      bool   compensate;
      double alpha = 0.;
    };
  } // namespace primal
} // namespace dualcontact
