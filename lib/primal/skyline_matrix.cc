#include <deal.II/base/exceptions.h>

#include <primal/skyline_matrix.h>

#include <algorithm>

namespace dualcontact
{
  namespace primal
  {
    SkylineMatrix::SkylineMatrix(const dealii::SparseMatrix<double> &matrix)
    {
      AssertThrow(matrix.m() == matrix.n(),
                  dealii::ExcMessage("SkylineMatrix: the matrix is not "
                                     "square"));
      const unsigned int n = matrix.m();
      first_column.resize(n);
      row_start.resize(n + 1);
      for (unsigned int i = 0; i < n; ++i)
      {
        unsigned int first = i;
        for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
          if (it->value() != 0.)
            first = std::min<unsigned int>(first, it->column());
        first_column[i]  = first;
        row_start[i + 1] = row_start[i] + (i - first + 1);
      }
      values.assign(row_start[n], 0.);
      for (unsigned int i = 0; i < n; ++i)
        for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
          if (it->column() <= i && it->value() != 0.)
            values[row_start[i] + it->column() - first_column[i]] = it->value();
    }


    void
    SkylineMatrix::vmult(VectorType &dst, const VectorType &src) const
    {
      const unsigned int n = first_column.size();
      AssertThrow(src.size() == n,
                  dealii::ExcMessage("SkylineMatrix: vector size differs"));
      dst.reinit(n);
      for (unsigned int i = 0; i < n; ++i)
      {
        const double *row   = values.data() + row_start[i];
        const double  x_i   = src(i);
        double        sum   = 0.;
        unsigned int  first = first_column[i];
        // the strictly lower part acts on row i and, by symmetry, on the
        // rows of its columns
        for (unsigned int j = first; j < i; ++j)
        {
          sum += row[j - first] * src(j);
          dst(j) += row[j - first] * x_i;
        }
        dst(i) += sum + row[i - first] * x_i;
      }
    }


    std::size_t
    SkylineMatrix::n_stored() const
    {
      return values.size();
    }
  } // namespace primal
} // namespace dualcontact
