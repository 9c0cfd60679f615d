#include <deal.II/base/exceptions.h>

#include <primal/incomplete_cholesky.h>

#include <cmath>

namespace dualcontact
{
  namespace primal
  {
    IncompleteCholesky::IncompleteCholesky(const bool diagonal_compensation)
        : compensate(diagonal_compensation)
    {
    }


    void
    IncompleteCholesky::initialize(const dealii::SparseMatrix<double> &matrix)
    {
      LowerTriangular lower;
      lower.copy_lower_part(matrix);
      for (unsigned int i = 0; i < lower.size(); ++i)
        AssertThrow(lower.diagonal[i] > 0.,
                    dealii::ExcMessage(
                      "incomplete Cholesky: diagonal entry " +
                      std::to_string(i) + " is " +
                      std::to_string(lower.diagonal[i]) +
                      " (the matrix is not positive definite)"));
      alpha = 0.;
      for (unsigned int attempt = 0; attempt <= 30; ++attempt)
      {
        if (factorize(lower, alpha))
          return;
        alpha = alpha == 0. ? 1e-3 : 2. * alpha;
      }
      AssertThrow(false,
                  dealii::ExcMessage("incomplete Cholesky: no positive "
                                     "pivots even with the diagonal shifted "
                                     "by " +
                                     std::to_string(alpha) + " diag(C)"));
    }


    bool
    IncompleteCholesky::factorize(const LowerTriangular &lower,
                                  const double           shift_factor)
    {
      E = lower;
      for (auto &d : E.diagonal)
        d *= 1. + shift_factor;
      const unsigned int n = E.size();
      for (unsigned int r = 0; r < n; ++r)
      {
        const double pivot = E.diagonal[r];
        if (!(pivot > 1e-12 * lower.diagonal[r]))
          return false;
        const std::size_t begin = E.column_start[r];
        const std::size_t end   = E.column_start[r + 1];
        // l_ir = c_ir / c_rr
        for (std::size_t k = begin; k < end; ++k)
          E.values[k] /= pivot;
        // c_ij -= l_ir c_rj = l_ir l_jr c_rr for i >= j > r
        for (std::size_t p = begin; p < end; ++p)
        {
          const unsigned int i   = E.row_index[p];
          const double       lir = E.values[p];
          E.diagonal[i] -= lir * lir * pivot;
          for (std::size_t q = begin; q < p; ++q)
          {
            const unsigned int j     = E.row_index[q]; // j < i
            const double       delta = -lir * E.values[q] * pivot;
            const long         pos   = E.find(i, j);
            if (pos >= 0)
              E.values[pos] += delta;
            else if (compensate)
            {
              // the dropped update of (i, j) and of (j, i)
              E.diagonal[i] += delta;
              E.diagonal[j] += delta;
            }
          }
        }
        // column r of E = L D^{1/2}
        const double s = std::sqrt(pivot);
        E.diagonal[r]  = s;
        for (std::size_t k = begin; k < end; ++k)
          E.values[k] *= s;
      }
      return true;
    }


    std::string
    IncompleteCholesky::name() const
    {
      return compensate ? "P-ILLD" : "P-ILL";
    }


    double
    IncompleteCholesky::shift() const
    {
      return alpha;
    }
  } // namespace primal
} // namespace dualcontact
