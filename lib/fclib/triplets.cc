#include <deal.II/base/exceptions.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <fclib/triplets.h>

namespace dualcontact
{
  namespace fclib
  {
    Triplets::Triplets(const unsigned int n_rows, const unsigned int n_cols)
        : n_rows_(n_rows)
        , n_cols_(n_cols)
    {
    }


    void
    Triplets::add(const unsigned int row,
                  const unsigned int col,
                  const double       value)
    {
      AssertThrow(row < n_rows_ && col < n_cols_,
                  dealii::ExcMessage("matrix entry (" + std::to_string(row) +
                                     ", " + std::to_string(col) +
                                     ") outside a " + std::to_string(n_rows_) +
                                     " x " + std::to_string(n_cols_) +
                                     " matrix"));
      AssertThrow(std::isfinite(value),
                  dealii::ExcMessage("non-finite matrix entry at (" +
                                     std::to_string(row) + ", " +
                                     std::to_string(col) + ")"));
      rows_.push_back(row);
      cols_.push_back(col);
      values_.push_back(value);
    }


    unsigned int
    Triplets::n_rows() const
    {
      return n_rows_;
    }


    unsigned int
    Triplets::n_cols() const
    {
      return n_cols_;
    }


    std::size_t
    Triplets::n_entries() const
    {
      return values_.size();
    }


    bool
    Triplets::upper_triangle_only() const
    {
      bool strictly_upper = false;
      for (std::size_t k = 0; k < rows_.size(); ++k)
      {
        if (rows_[k] > cols_[k] && values_[k] != 0.)
          return false;
        if (rows_[k] < cols_[k] && values_[k] != 0.)
          strictly_upper = true;
      }
      return strictly_upper;
    }


    void
    Triplets::symmetrize_from_upper()
    {
      const std::size_t n = rows_.size();
      for (std::size_t k = 0; k < n; ++k)
        if (rows_[k] < cols_[k])
        {
          rows_.push_back(cols_[k]);
          cols_.push_back(rows_[k]);
          values_.push_back(values_[k]);
        }
    }


    void
    Triplets::build(dealii::SparsityPattern      &pattern,
                    dealii::SparseMatrix<double> &matrix) const
    {
      dealii::DynamicSparsityPattern dsp(n_rows_, n_cols_);
      for (std::size_t k = 0; k < rows_.size(); ++k)
        dsp.add(rows_[k], cols_[k]);
      if (n_rows_ == n_cols_)
        for (unsigned int i = 0; i < n_rows_; ++i)
          dsp.add(i, i);
      pattern.copy_from(dsp);
      matrix.reinit(pattern);
      for (std::size_t k = 0; k < rows_.size(); ++k)
        matrix.add(rows_[k], cols_[k], values_[k]);
    }


    const std::vector<unsigned int> &
    Triplets::rows() const
    {
      return rows_;
    }


    const std::vector<unsigned int> &
    Triplets::cols() const
    {
      return cols_;
    }


    const std::vector<double> &
    Triplets::values() const
    {
      return values_;
    }


    OwnedSparseMatrix::OwnedSparseMatrix(const Triplets &triplets)
        : pattern(std::make_unique<dealii::SparsityPattern>())
    {
      triplets.build(*pattern, matrix);
    }


    Triplets
    OwnedSparseMatrix::to_triplets() const
    {
      Triplets t(matrix.m(), matrix.n());
      for (unsigned int i = 0; i < matrix.m(); ++i)
        for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
          if (it->value() != 0.)
            t.add(i, it->column(), it->value());
      return t;
    }
  } // namespace fclib
} // namespace dualcontact
