#pragma once

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <memory>
#include <vector>

namespace dualcontact
{
  namespace fclib
  {
    /**
     * A sparse matrix being assembled from (row, column, value) entries, and
     * the deal.II matrix made from it.
     *
     * Why: FCLIB files hold matrices in three layouts (triplets, compressed
     * columns, compressed rows) and two of the distributed files store only
     * the upper triangle of a symmetric M; everything is turned into this one
     * form first, duplicates summed, and then into a deal.II SparseMatrix
     * (what CHOLMOD/UMFPACK and the products need).
     */
    class Triplets
    {
    public:
      Triplets(const unsigned int n_rows, const unsigned int n_cols);

      /** Add @p value at (@p row, @p col); out-of-range indices throw. */
      void
      add(const unsigned int row, const unsigned int col, const double value);

      unsigned int
      n_rows() const;
      unsigned int
      n_cols() const;
      std::size_t
      n_entries() const;

      /**
       * Whether every entry lies on or above the diagonal and some lies
       * strictly above it: the storage of only the upper triangle of a
       * symmetric matrix.
       */
      bool
      upper_triangle_only() const;

      /** Add the mirror image (col, row) of every strictly upper entry. */
      void
      symmetrize_from_upper();

      /**
       * Build @p pattern and @p matrix (duplicates summed; the pattern gets a
       * diagonal entry in every row of a square matrix, as deal.II wants).
       */
      void
      build(dealii::SparsityPattern      &pattern,
            dealii::SparseMatrix<double> &matrix) const;

      const std::vector<unsigned int> &
      rows() const;
      const std::vector<unsigned int> &
      cols() const;
      const std::vector<double> &
      values() const;

    private:
      unsigned int              n_rows_, n_cols_;
      std::vector<unsigned int> rows_, cols_;
      std::vector<double>       values_;
    };


    /**
     * A deal.II sparse matrix with its own sparsity pattern (the matrix keeps
     * a pointer to the pattern, so both live together; movable, not
     * copyable).
     */
    struct OwnedSparseMatrix
    {
      OwnedSparseMatrix() = default;
      explicit OwnedSparseMatrix(const Triplets &triplets);

      /** Entries of the matrix as triplets (row by row). */
      Triplets
      to_triplets() const;

      std::unique_ptr<dealii::SparsityPattern> pattern;
      dealii::SparseMatrix<double>             matrix;
    };
  } // namespace fclib
} // namespace dualcontact
