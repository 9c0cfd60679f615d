#pragma once

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace dualcontact
{
  namespace primal
  {
    /**
     * A sparse lower triangular matrix E (diagonal plus strictly lower part
     * stored by columns), the factor W = E E' of the SSOR and incomplete
     * Cholesky preconditioners.
     *
     * Why by columns: the incomplete factorization of the report (section
     * 10) is right-looking Gaussian elimination -- step r divides column r
     * by the pivot and updates the entries (i, j), i >= j > r, of the
     * remaining matrix from pairs of column r's entries -- and both
     * triangular solves run along columns as well.
     */
    class LowerTriangular
    {
    public:
      using VectorType = dealii::Vector<double>;

      /** The diagonal and the strictly lower part of @p matrix (its
       * pattern, explicit zeros dropped), rows sorted in each column. */
      void
      copy_lower_part(const dealii::SparseMatrix<double> &matrix);

      unsigned int
      size() const;

      /** Index into values() of the entry (i, j), i > j, or -1 if (i, j) is
       * not in the pattern. */
      long
      find(const unsigned int i, const unsigned int j) const;

      /** x := E^{-1} x (forward substitution). */
      void
      solve(VectorType &x) const;
      /** x := E^{-T} x (backward substitution). */
      void
      solve_transpose(VectorType &x) const;
      /** dst = E src. */
      void
      vmult(VectorType &dst, const VectorType &src) const;
      /** dst = E' src. */
      void
      Tvmult(VectorType &dst, const VectorType &src) const;

      /** Number of stored entries below the diagonal. */
      std::size_t
      n_off_diagonal() const;

      /** The diagonal, and the strictly lower part: column j holds rows
       * row_index[k] with values[k] for k in [column_start[j],
       * column_start[j+1]). */
      std::vector<double>       diagonal;
      std::vector<std::size_t>  column_start;
      std::vector<unsigned int> row_index;
      std::vector<double>       values;
    };
  } // namespace primal
} // namespace dualcontact
