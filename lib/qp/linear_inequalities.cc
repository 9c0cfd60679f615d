#include <qp/linear_inequalities.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/trilinos_vector.h>

#include <algorithm>
#include <cmath>

namespace dualcontact
{
  namespace qp
  {
    namespace
    {
      // scattered additions: direct for a serial vector, add() + compress()
      // for a Trilinos vector (whose element writes must be compressed)
      void
      scatter_add(dealii::Vector<double>                             &dst,
                  const std::vector<dealii::types::global_dof_index> &index,
                  const std::vector<double>                          &value)
      {
        for (std::size_t k = 0; k < index.size(); ++k)
          dst(index[k]) += value[k];
      }

      void
      scatter_add(dealii::TrilinosWrappers::MPI::Vector              &dst,
                  const std::vector<dealii::types::global_dof_index> &index,
                  const std::vector<double>                          &value)
      {
        dst.add(index, value);
        dst.compress(dealii::VectorOperation::add);
      }
    } // namespace


    void
    LinearInequalities::add_row(const std::vector<size_type> &row_columns,
                                const std::vector<double>    &row_values,
                                const double                  row_rhs)
    {
      AssertThrow(row_columns.size() == row_values.size(),
                  dealii::ExcMessage(
                    "LinearInequalities::add_row: " +
                    std::to_string(row_columns.size()) + " columns but " +
                    std::to_string(row_values.size()) + " values"));
      AssertThrow(std::isfinite(row_rhs),
                  dealii::ExcMessage(
                    "LinearInequalities::add_row: right-hand side of row " +
                    std::to_string(rhs.size()) + " is not finite"));
      double sq = 0.;
      for (std::size_t k = 0; k < row_columns.size(); ++k)
      {
        AssertThrow(std::isfinite(row_values[k]),
                    dealii::ExcMessage("LinearInequalities::add_row: "
                                       "non-finite coefficient in row " +
                                       std::to_string(rhs.size())));
        columns.push_back(row_columns[k]);
        values.push_back(row_values[k]);
        max_column = std::max(max_column, row_columns[k] + 1);
        sq += row_values[k] * row_values[k];
      }
      AssertThrow(sq > 0.,
                  dealii::ExcMessage("LinearInequalities::add_row: row " +
                                     std::to_string(rhs.size()) +
                                     " is zero (a constraint 0 <= c is "
                                     "either void or infeasible)"));
      row_start.push_back(columns.size());
      rhs.push_back(row_rhs);
      norm_sq.push_back(sq);
      orthogonal = -1;
    }


    void
    LinearInequalities::add_lower_bound(const size_type index,
                                        const double    lower)
    {
      add_row({index}, {-1.}, -lower);
    }


    void
    LinearInequalities::add_upper_bound(const size_type index,
                                        const double    upper)
    {
      add_row({index}, {1.}, upper);
    }


    void
    LinearInequalities::add_rows(const dealii::SparseMatrix<double> &matrix,
                                 const dealii::Vector<double>       &c)
    {
      AssertThrow(matrix.m() == c.size(),
                  dealii::ExcMessage("LinearInequalities::add_rows: matrix "
                                     "has " +
                                     std::to_string(matrix.m()) +
                                     " rows, right-hand side " +
                                     std::to_string(c.size())));
      std::vector<size_type> cols;
      std::vector<double>    vals;
      for (unsigned int r = 0; r < matrix.m(); ++r)
      {
        cols.clear();
        vals.clear();
        for (auto it = matrix.begin(r); it != matrix.end(r); ++it)
          if (it->value() != 0.)
          {
            cols.push_back(it->column());
            vals.push_back(it->value());
          }
        add_row(cols, vals, c[r]);
      }
    }


    LinearInequalities::size_type
    LinearInequalities::n_rows() const
    {
      return rhs.size();
    }


    LinearInequalities::size_type
    LinearInequalities::min_columns() const
    {
      return max_column;
    }


    bool
    LinearInequalities::rows_orthogonal() const
    {
      if (orthogonal < 0)
      {
        std::vector<size_type> sorted(columns);
        std::sort(sorted.begin(), sorted.end());
        orthogonal =
          std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end() ? 1 :
                                                                             0;
      }
      return orthogonal == 1;
    }


    template <typename VectorType>
    double
    LinearInequalities::row_dot(const size_type i, const VectorType &x) const
    {
      double sum = 0.;
      for (std::size_t k = row_start[i]; k < row_start[i + 1]; ++k)
        sum += values[k] * x[columns[k]];
      return sum;
    }


    template <typename VectorType>
    double
    LinearInequalities::row_abs_dot(const size_type   i,
                                    const VectorType &x) const
    {
      double sum = 0.;
      for (std::size_t k = row_start[i]; k < row_start[i + 1]; ++k)
        sum += std::abs(values[k] * x[columns[k]]);
      return sum;
    }


    template <typename VectorType>
    void
    LinearInequalities::add_transpose(const std::vector<size_type> &rows,
                                      const std::vector<double>    &weights,
                                      VectorType                   &dst) const
    {
      Assert(rows.size() == weights.size(), dealii::ExcInternalError());
      std::vector<size_type> index;
      std::vector<double>    value;
      for (std::size_t r = 0; r < rows.size(); ++r)
        for (std::size_t k = row_start[rows[r]]; k < row_start[rows[r] + 1];
             ++k)
        {
          index.push_back(columns[k]);
          value.push_back(weights[r] * values[k]);
        }
      scatter_add(dst, index, value);
    }


    double
    LinearInequalities::row_norm_sq(const size_type i) const
    {
      return norm_sq[i];
    }


    double
    LinearInequalities::right_hand_side(const size_type i) const
    {
      return rhs[i];
    }


    unsigned int
    LinearInequalities::row_length(const size_type i) const
    {
      return row_start[i + 1] - row_start[i];
    }


    LinearInequalities::size_type
    LinearInequalities::first_column(const size_type i) const
    {
      return columns[row_start[i]];
    }


    double
    LinearInequalities::first_value(const size_type i) const
    {
      return values[row_start[i]];
    }


    double
    LinearInequalities::row_product(const size_type i, const size_type j) const
    {
      // columns of a row are not necessarily sorted: quadratic merge is
      // fine for the short rows of contact constraints
      double sum = 0.;
      for (std::size_t k = row_start[i]; k < row_start[i + 1]; ++k)
        for (std::size_t l = row_start[j]; l < row_start[j + 1]; ++l)
          if (columns[k] == columns[l])
            sum += values[k] * values[l];
      return sum;
    }


    template double
    LinearInequalities::row_dot(const size_type,
                                const dealii::Vector<double> &) const;
    template double
    LinearInequalities::row_dot(
      const size_type,
      const dealii::TrilinosWrappers::MPI::Vector &) const;
    template double
    LinearInequalities::row_abs_dot(const size_type,
                                    const dealii::Vector<double> &) const;
    template double
    LinearInequalities::row_abs_dot(
      const size_type,
      const dealii::TrilinosWrappers::MPI::Vector &) const;
    template void
    LinearInequalities::add_transpose(const std::vector<size_type> &,
                                      const std::vector<double> &,
                                      dealii::Vector<double> &) const;
    template void
    LinearInequalities::add_transpose(
      const std::vector<size_type> &,
      const std::vector<double> &,
      dealii::TrilinosWrappers::MPI::Vector &) const;
  } // namespace qp
} // namespace dualcontact
