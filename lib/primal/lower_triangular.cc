#include <deal.II/base/exceptions.h>

#include <primal/lower_triangular.h>

#include <algorithm>

namespace dualcontact
{
  namespace primal
  {
    void
    LowerTriangular::copy_lower_part(const dealii::SparseMatrix<double> &matrix)
    {
      AssertThrow(matrix.m() == matrix.n(),
                  dealii::ExcMessage("LowerTriangular: the matrix is not "
                                     "square"));
      const unsigned int n = matrix.m();
      diagonal.assign(n, 0.);
      // count the entries of each column of the strictly lower part; a row
      // of the deal.II matrix lists the columns j < i of row i, i.e. the
      // entry (i, j) goes to column j
      std::vector<std::size_t> count(n + 1, 0);
      for (unsigned int i = 0; i < n; ++i)
        for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
          if (it->column() < i && it->value() != 0.)
            ++count[it->column() + 1];
      column_start.assign(n + 1, 0);
      for (unsigned int j = 0; j < n; ++j)
        column_start[j + 1] = column_start[j] + count[j + 1];
      row_index.assign(column_start[n], 0);
      values.assign(column_start[n], 0.);
      std::vector<std::size_t> next(column_start.begin(),
                                    column_start.end() - 1);
      // rows in increasing order, so each column comes out sorted
      for (unsigned int i = 0; i < n; ++i)
        for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
        {
          const unsigned int j = it->column();
          if (j == i)
            diagonal[i] = it->value();
          else if (j < i && it->value() != 0.)
          {
            row_index[next[j]] = i;
            values[next[j]]    = it->value();
            ++next[j];
          }
        }
    }


    unsigned int
    LowerTriangular::size() const
    {
      return diagonal.size();
    }


    long
    LowerTriangular::find(const unsigned int i, const unsigned int j) const
    {
      const auto begin = row_index.begin() + column_start[j];
      const auto end   = row_index.begin() + column_start[j + 1];
      const auto it    = std::lower_bound(begin, end, i);
      if (it == end || *it != i)
        return -1;
      return it - row_index.begin();
    }


    void
    LowerTriangular::solve(VectorType &x) const
    {
      AssertDimension(x.size(), size());
      for (unsigned int j = 0; j < size(); ++j)
      {
        const double xj = x(j) / diagonal[j];
        x(j)            = xj;
        for (std::size_t k = column_start[j]; k < column_start[j + 1]; ++k)
          x(row_index[k]) -= values[k] * xj;
      }
    }


    void
    LowerTriangular::solve_transpose(VectorType &x) const
    {
      AssertDimension(x.size(), size());
      for (unsigned int j = size(); j-- > 0;)
      {
        double sum = x(j);
        for (std::size_t k = column_start[j]; k < column_start[j + 1]; ++k)
          sum -= values[k] * x(row_index[k]);
        x(j) = sum / diagonal[j];
      }
    }


    void
    LowerTriangular::vmult(VectorType &dst, const VectorType &src) const
    {
      AssertDimension(src.size(), size());
      dst.reinit(size());
      for (unsigned int j = 0; j < size(); ++j)
      {
        dst(j) += diagonal[j] * src(j);
        for (std::size_t k = column_start[j]; k < column_start[j + 1]; ++k)
          dst(row_index[k]) += values[k] * src(j);
      }
    }


    void
    LowerTriangular::Tvmult(VectorType &dst, const VectorType &src) const
    {
      AssertDimension(src.size(), size());
      dst.reinit(size());
      for (unsigned int j = 0; j < size(); ++j)
      {
        double sum = diagonal[j] * src(j);
        for (std::size_t k = column_start[j]; k < column_start[j + 1]; ++k)
          sum += values[k] * src(row_index[k]);
        dst(j) = sum;
      }
    }


    std::size_t
    LowerTriangular::n_off_diagonal() const
    {
      return values.size();
    }
  } // namespace primal
} // namespace dualcontact
