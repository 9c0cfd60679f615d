#include <deal.II/base/exceptions.h>

#include <fclib/delassus_operator.h>
#include <util/blas.h>

#include <algorithm>
#include <cmath>


namespace dualcontact
{
  namespace fclib
  {
    namespace
    {
      /** Fraction of non-zero entries from which W is stored dense. */
      constexpr double dense_density = 0.25;

      /** y = A x with a column-major symmetric n x n A (upper triangle). */
      void
      symv(const std::vector<double>    &A,
           const unsigned int            n,
           const dealii::Vector<double> &x,
           dealii::Vector<double>       &y)
      {
        const int    size = n, one = 1;
        const double alpha = 1., beta = 0.;
        dsymv_("U",
               &size,
               &alpha,
               A.data(),
               &size,
               x.data(),
               &one,
               &beta,
               y.data(),
               &one);
      }
    } // namespace


    DelassusOperator::DelassusOperator(const Triplets &W, const Storage storage)
        : n_(W.n_rows())
        , W_(W)
    {
      AssertThrow(W.n_rows() == W.n_cols(),
                  dealii::ExcMessage(
                    "the Delassus matrix W is " + std::to_string(W.n_rows()) +
                    " x " + std::to_string(W.n_cols()) + ", not square"));
      const dealii::SparseMatrix<double> &A       = W_.matrix;
      double                              largest = 0, difference = 0;
      for (unsigned int i = 0; i < n_; ++i)
      {
        bool empty = true;
        for (auto it = A.begin(i); it != A.end(i); ++it)
          empty = empty && it->value() == 0.;
        zero_rows_ += empty;
      }
      for (unsigned int i = 0; i < n_; ++i)
        for (auto it = A.begin(i); it != A.end(i); ++it)
          if (it->value() != 0.)
          {
            ++nonzero_;
            largest = std::max(largest, std::abs(it->value()));
            difference =
              std::max(difference,
                       std::abs(it->value() - A.el(it->column(), i)));
          }
      asymmetry_           = largest > 0 ? difference / largest : 0.;
      const bool symmetric = difference == 0.;

      const double size2 = double(n_) * double(n_);
      dense_             = storage == Storage::dense ||
               (storage == Storage::automatic && n_ > 0 &&
                double(nonzero_) >= dense_density * size2);
      if (dense_)
      {
        dense_W_.assign(std::size_t(n_) * n_, 0.);
        for (unsigned int i = 0; i < n_; ++i)
          for (auto it = A.begin(i); it != A.end(i); ++it)
            dense_W_[i + std::size_t(it->column()) * n_] = it->value();
        if (!symmetric)
        {
          dense_W_s_.resize(dense_W_.size());
          for (unsigned int j = 0; j < n_; ++j)
            for (unsigned int i = 0; i < n_; ++i)
              dense_W_s_[i + std::size_t(j) * n_] =
                0.5 * (dense_W_[i + std::size_t(j) * n_] +
                       dense_W_[j + std::size_t(i) * n_]);
        }
      }
      else if (!symmetric)
      {
        Triplets half(n_, n_);
        for (unsigned int i = 0; i < n_; ++i)
          for (auto it = A.begin(i); it != A.end(i); ++it)
            if (it->value() != 0.)
            {
              half.add(i, it->column(), 0.5 * it->value());
              half.add(it->column(), i, 0.5 * it->value());
            }
        W_s_ = OwnedSparseMatrix(half);
      }
      work_.reinit(n_);
    }


    unsigned int
    DelassusOperator::size() const
    {
      return n_;
    }


    bool
    DelassusOperator::dense() const
    {
      return dense_;
    }


    std::size_t
    DelassusOperator::n_nonzero() const
    {
      return nonzero_;
    }


    const dealii::SparseMatrix<double> &
    DelassusOperator::matrix() const
    {
      return W_.matrix;
    }


    unsigned int
    DelassusOperator::n_zero_rows() const
    {
      return zero_rows_;
    }


    double
    DelassusOperator::asymmetry() const
    {
      return asymmetry_;
    }


    void
    DelassusOperator::vmult(dealii::Vector<double>       &dst,
                            const dealii::Vector<double> &src) const
    {
      Assert(src.size() == n_, dealii::ExcDimensionMismatch(src.size(), n_));
      dst.reinit(n_, true);
      if (n_ == 0)
        return;
      if (!dense_)
      {
        W_.matrix.vmult(dst, src);
        return;
      }
      if (dense_W_s_.empty()) // symmetric: one triangle suffices
      {
        symv(dense_W_, n_, src, dst);
        return;
      }
      const int    size = n_, one = 1;
      const double alpha = 1., beta = 0.;
      dgemv_("N",
             &size,
             &size,
             &alpha,
             dense_W_.data(),
             &size,
             src.data(),
             &one,
             &beta,
             dst.data(),
             &one);
    }


    void
    DelassusOperator::symmetric_vmult(dealii::Vector<double>       &dst,
                                      const dealii::Vector<double> &src) const
    {
      Assert(src.size() == n_, dealii::ExcDimensionMismatch(src.size(), n_));
      dst.reinit(n_, true);
      if (n_ == 0)
        return;
      if (dense_)
        symv(dense_W_s_.empty() ? dense_W_ : dense_W_s_, n_, src, dst);
      else if (W_s_.pattern)
        W_s_.matrix.vmult(dst, src);
      else
        W_.matrix.vmult(dst, src);
    }


    std::vector<double>
    DelassusOperator::scaled_dense_symmetric(
      const dealii::Vector<double> &s) const
    {
      AssertThrow(s.size() == n_, dealii::ExcDimensionMismatch(s.size(), n_));
      if (!dense_)
        return {};
      std::vector<double> A = dense_W_s_.empty() ? dense_W_ : dense_W_s_;
      for (unsigned int j = 0; j < n_; ++j)
        for (unsigned int i = 0; i < n_; ++i)
          A[i + std::size_t(j) * n_] *= s(i) * s(j);
      return A;
    }


    void
    DelassusOperator::dense_vmult(const std::vector<double>    &A,
                                  dealii::Vector<double>       &dst,
                                  const dealii::Vector<double> &src)
    {
      const unsigned int n = src.size();
      Assert(A.size() == std::size_t(n) * n,
             dealii::ExcDimensionMismatch(A.size(), std::size_t(n) * n));
      dst.reinit(n, true);
      if (n > 0)
        symv(A, n, src, dst);
    }


    void
    DelassusOperator::dense_add_columns(const std::vector<double>      &A,
                                        dealii::Vector<double>         &dst,
                                        const dealii::Vector<double>   &v,
                                        const std::vector<std::size_t> &indices)
    {
      const std::size_t n = dst.size();
      Assert(A.size() == n * n, dealii::ExcDimensionMismatch(A.size(), n * n));
      double *out = dst.data();
      for (const std::size_t j : indices)
      {
        const double  vj     = v(j);
        const double *column = A.data() + j * n;
        for (std::size_t i = 0; i < n; ++i)
          out[i] += column[i] * vj;
      }
    }


    void
    DelassusOperator::add_symmetric_columns(
      dealii::Vector<double>         &dst,
      const dealii::Vector<double>   &v,
      const std::vector<std::size_t> &indices) const
    {
      Assert(dst.size() == n_ && v.size() == n_,
             dealii::ExcDimensionMismatch(dst.size(), n_));
      if (dense_)
        dense_add_columns(dense_W_s_.empty() ? dense_W_ : dense_W_s_,
                          dst,
                          v,
                          indices);
      else
      {
        // W_s is symmetric: column j is row j
        const dealii::SparseMatrix<double> &S =
          W_s_.pattern ? W_s_.matrix : W_.matrix;
        for (const std::size_t j : indices)
        {
          const double vj = v(j);
          for (auto it = S.begin(j); it != S.end(j); ++it)
            dst(it->column()) += it->value() * vj;
        }
      }
    }


    void
    DelassusOperator::antisymmetric_vmult(
      dealii::Vector<double>       &dst,
      const dealii::Vector<double> &src) const
    {
      vmult(dst, src);
      symmetric_vmult(work_, src);
      dst -= work_;
    }


    int
    DelassusOperator::numerical_rank(const double       relative_tolerance,
                                     const unsigned int max_size) const
    {
      if (n_ > max_size)
        return -1;
      if (n_ == 0)
        return 0;
      // W_s dense, column-major (upper triangle used)
      std::vector<double> A;
      if (dense_)
        A = dense_W_s_.empty() ? dense_W_ : dense_W_s_;
      else
      {
        A.assign(std::size_t(n_) * n_, 0.);
        const dealii::SparseMatrix<double> &S =
          W_s_.pattern ? W_s_.matrix : W_.matrix;
        for (unsigned int i = 0; i < n_; ++i)
          for (auto it = S.begin(i); it != S.end(i); ++it)
            A[i + std::size_t(it->column()) * n_] = it->value();
      }
      double largest = 0;
      for (unsigned int i = 0; i < n_; ++i)
        largest = std::max(largest, A[i + std::size_t(i) * n_]);
      if (!(largest > 0))
        return 0;
      const int           size = n_;
      int                 rank = 0, info = 0;
      const double        tol = relative_tolerance * largest;
      std::vector<int>    piv(n_);
      std::vector<double> work(2 * std::size_t(n_));
      dpstrf_("U",
              &size,
              A.data(),
              &size,
              piv.data(),
              &rank,
              &tol,
              work.data(),
              &info);
      AssertThrow(info >= 0,
                  dealii::ExcMessage("LAPACK dpstrf failed on W_s (info " +
                                     std::to_string(info) + ")"));
      return info == 0 ? size : rank;
    }
  } // namespace fclib
} // namespace dualcontact
