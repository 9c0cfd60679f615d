/**
 * @file linear_inequalities.h
 * Sparse linear inequality constraints  a_i'x <= c_i  (rows of a sparse
 * matrix A), the constraint type of the conjugate projected gradient method
 * CGC (Kestranek & Nedoma 1996, sections 6-7), used by the primal Uzawa
 * baseline.  Unlike a SeparableSet, rows may couple any unknowns (e.g. the
 * non-penetration condition u_N^1 - u_N^2 <= gap between two bodies), so
 * the projection onto a facet needs the Gram matrix A_J A_J'.
 */
#ifndef dualcontact_qp_linear_inequalities_h
#define dualcontact_qp_linear_inequalities_h

#include <deal.II/base/types.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace dualcontact
{
  namespace qp
  {
    /**
     * The rows a_i, right-hand sides c_i of A x <= c, stored row-compressed
     * with global column indices.  Operations read and write vector entries
     * by global index, so with a distributed vector every row must refer to
     * locally owned entries (CGC is run on one process; checked there).
     */
    class LinearInequalities
    {
    public:
      using size_type = dealii::types::global_dof_index;

      /// Add the row  sum_k values[k] x_{columns[k]} <= rhs.
      void
      add_row(const std::vector<size_type> &columns,
              const std::vector<double>    &values,
              const double                  rhs);

      /// x_i >= lower, i.e. -x_i <= -lower.
      void
      add_lower_bound(const size_type index, const double lower);
      /// x_i <= upper.
      void
      add_upper_bound(const size_type index, const double upper);

      /// Every row of @p matrix with the entry of @p rhs.
      void
      add_rows(const dealii::SparseMatrix<double> &matrix,
               const dealii::Vector<double>       &rhs);

      size_type
      n_rows() const;
      /// largest column index + 1 (0 if no rows)
      size_type
      min_columns() const;

      /**
       * True if no column appears in two rows: then the rows are mutually
       * orthogonal, A_J A_J' is diagonal for every J, and (report, lemma
       * 7.2) all constraints with negative multipliers may be released at
       * once.  Bound constraints have this property.
       */
      bool
      rows_orthogonal() const;

      /// a_i'x
      template <typename VectorType>
      double
      row_dot(const size_type i, const VectorType &x) const;

      /// sum_k |a_ik x_k|: the scale of the rounding error of a_i'x
      template <typename VectorType>
      double
      row_abs_dot(const size_type i, const VectorType &x) const;

      /// c_i - a_i'x (>= 0 when row i is satisfied)
      template <typename VectorType>
      double
      slack(const size_type i, const VectorType &x) const
      {
        return rhs[i] - row_dot(i, x);
      }

      /// dst += sum_{k} weights[k] a_{rows[k]}  (dst += A_J' w)
      template <typename VectorType>
      void
      add_transpose(const std::vector<size_type> &rows,
                    const std::vector<double>    &weights,
                    VectorType                   &dst) const;

      /// ||a_i||^2
      double
      row_norm_sq(const size_type i) const;

      /// c_i
      double
      right_hand_side(const size_type i) const;

      /// number of entries of row i and its single column if it has one
      /// entry (used to put x exactly on a bound)
      unsigned int
      row_length(const size_type i) const;
      size_type
      first_column(const size_type i) const;
      double
      first_value(const size_type i) const;

      /// a_{i}'a_{j} (sparse merge)
      double
      row_product(const size_type i, const size_type j) const;

    private:
      std::vector<std::size_t> row_start = {0};
      std::vector<size_type>   columns;
      std::vector<double>      values;
      std::vector<double>      rhs;
      std::vector<double>      norm_sq;
      size_type                max_column = 0;
      /// cached result of rows_orthogonal(), -1 = unknown
      mutable int orthogonal = -1;
    };
  } // namespace qp
} // namespace dualcontact

#endif
