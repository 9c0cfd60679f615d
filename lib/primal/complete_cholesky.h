#pragma once

#include <primal/preconditioner.h>

#include <memory>

namespace dualcontact
{
  namespace primal
  {
    /**
     * The complete Cholesky factorization as a preconditioner (report: P-LL;
     * "in the SKY-LINE format it is the best to carry out the complete
     * factorization"): C = L L' by CHOLMOD (supernodal or simplicial, always
     * in the L L' form) in the natural order of the unknowns, as the
     * report's profile factor: W = C, E = L lower triangular.
     *
     * Why no fill-reducing permutation P: E = P'L would not be triangular,
     * and PCG-2's operator (I - P_J) E^{-T} (I - P_J) E^{-1} (I - P_J) can
     * then be singular on a facet (for bound rows J it is regular iff E_JJ
     * is, which holds for triangular E).  Measured: with CHOLMOD's AMD
     * order CGC stagnated at a projected gradient of 0.65 ||b|| on a block
     * on a plane (tests/primal/uzawa_vs_dual), in natural order it
     * converges.  The solves still go through CHOLMOD's P (the identity).
     *
     * Why not fem::CholmodSolver: that class applies C^{-1} as a whole;
     * PCG-1 and PCG-2 need the two triangular halves separately.
     */
    class CompleteCholesky : public Preconditioner
    {
    public:
      CompleteCholesky();
      ~CompleteCholesky() override;

      void
      initialize(const dealii::SparseMatrix<double> &matrix) override;
      void
      apply_E_inverse(VectorType &dst, const VectorType &src) const override;
      void
      apply_E_inverse_transpose(VectorType       &dst,
                                const VectorType &src) const override;
      std::string
      name() const override;

      /** Number of non-zeros of L. */
      double
      factor_nonzeros() const;

    private:
      /** Apply the CHOLMOD solves @p systems (CHOLMOD_P, CHOLMOD_L, ...) in
       * this order. */
      void
      apply(VectorType             &dst,
            const VectorType       &src,
            const std::vector<int> &systems) const;

      struct Data;
      std::unique_ptr<Data> data;
    };
  } // namespace primal
} // namespace dualcontact
