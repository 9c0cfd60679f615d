#pragma once

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <string>

namespace dualcontact
{
  namespace primal
  {
    /**
     * A preconditioner W = E E' of the stiffness matrix C, given by its
     * factor E (Kestranek & Nedoma 1996, sections 8-10).
     *
     * Why the factor and not W^{-1}: the report's two preconditioned CG
     * versions use E^{-1} and E^{-T} separately.  PCG-1 (section 8) is CG on
     * the transformed problem in y = E'x, with Hessian E^{-1} C E^{-T} and
     * constraint rows A E^{-T}; PCG-2 (section 9) projects before and after
     * each factor, g = (I - P) E^{-1} (I - P) r, v = -(I - P) E^{-T} g.  Only
     * for W = C (complete Cholesky) and PCG-1 is the transformed Hessian the
     * identity, which is why the report's P-LL(1) needs 2 inner iterations
     * and P-LL(2) 18.
     */
    class Preconditioner
    {
    public:
      using VectorType = dealii::Vector<double>;

      virtual ~Preconditioner() = default;

      /** Build W for the SPD matrix @p matrix (kept by reference only
       * where a derived class says so). */
      virtual void
      initialize(const dealii::SparseMatrix<double> &matrix) = 0;

      /** dst = E^{-1} src. */
      virtual void
      apply_E_inverse(VectorType &dst, const VectorType &src) const = 0;

      /** dst = E^{-T} src. */
      virtual void
      apply_E_inverse_transpose(VectorType       &dst,
                                const VectorType &src) const = 0;

      /** dst = W^{-1} src = E^{-T} E^{-1} src. */
      void
      apply_inverse(VectorType &dst, const VectorType &src) const;

      /** The report's name: "P-DIAG", "P-SOR", "P-ILL", "P-ILLD", "P-LL". */
      virtual std::string
      name() const = 0;

      /**
       * The preconditioner named @p type in the parameter file: `diagonal`,
       * `ssor` (with relaxation @p omega in (0, 2)), `ic` (incomplete
       * Cholesky), `icd` (incomplete Cholesky with the dropped fill added to
       * the diagonal), `cholesky` (complete, CHOLMOD).  `none` gives a null
       * pointer.  Throws for anything else.
       */
      static std::unique_ptr<Preconditioner>
      create(const std::string &type, const double omega = 1.);
    };
  } // namespace primal
} // namespace dualcontact
