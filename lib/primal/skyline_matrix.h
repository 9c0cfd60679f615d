#pragma once

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace dualcontact
{
  namespace primal
  {
    /**
     * A symmetric matrix in SKY-LINE (profile) storage, the report's second
     * storage format of C (remark 5.1, tables 11.1, 11.2, 11.8, 11.11): row
     * i keeps every entry of its lower triangle from its first non-zero
     * column to the diagonal, zeros inside the profile included.  The
     * report's SKY-LINE rows are CG without preconditioning on C in this
     * format; the product is the same as the sparse one up to the order of
     * the sums (its inner iterations 547/557 against SPARSE's 547/558).
     */
    class SkylineMatrix
    {
    public:
      using VectorType = dealii::Vector<double>;

      /** Copies the lower profile of the symmetric @p matrix. */
      explicit SkylineMatrix(const dealii::SparseMatrix<double> &matrix);

      /** dst = C src, row by row through the profile. */
      void
      vmult(VectorType &dst, const VectorType &src) const;

      /** Entries stored (the report's NWK). */
      std::size_t
      n_stored() const;

    private:
      /** first non-zero column of every row */
      std::vector<unsigned int> first_column;
      /** offset of row i's first stored entry in values */
      std::vector<std::size_t> row_start;
      /** row i: columns first_column[i] .. i */
      std::vector<double> values;
    };
  } // namespace primal
} // namespace dualcontact
