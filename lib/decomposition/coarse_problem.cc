#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <decomposition/coarse_problem.h>

#include <algorithm>

namespace dualcontact
{
  namespace decomposition
  {
    namespace
    {
      /**
       * Factorizes @p matrix; false where it is singular: a pivot that is
       * not positive, or a reciprocal condition number (smallest over
       * largest pivot) below 1e-12, the relative pivot under which the
       * dense Cholesky that came before took a direction for a kernel one.
       */
      bool
      factorize(fem::CholmodSolver                 &solver,
                const dealii::SparseMatrix<double> &matrix)
      {
        try
        {
          solver.initialize(matrix);
        }
        catch (const std::exception &)
        {
          return false;
        }
        return solver.reciprocal_condition() > 1e-12;
      }
    } // namespace


    CoarseProblem::CoarseProblem(const unsigned int n_modes, Columns columns)
        : n_modes_(n_modes)
        , columns_(std::move(columns))
    {
      dealii::Timer timer;
      assemble_normal_matrix([](unsigned int) { return true; }, pattern_, ggt_);
      factor_ = std::make_unique<fem::CholmodSolver>();
      // a singular G G' (CHOLMOD stops at a pivot that is not positive,
      // or round-off leaves a tiny one) is a combination of rigid-body
      // modes that no row of B (no support, gluing or contact) touches
      AssertThrow(factorize(*factor_, ggt_),
                  dealii::ExcMessage(
                    "A rigid-body motion of a body is not restrained by "
                    "any contact constraint (G = R'B' is rank deficient): "
                    "add a Dirichlet condition, a contact pair or friction "
                    "that holds it."));
      setup_time_ = timer.wall_time();
    }


    unsigned int
    CoarseProblem::n_modes() const
    {
      return n_modes_;
    }


    void
    CoarseProblem::vmult(dealii::Vector<double>       &dst,
                         const dealii::Vector<double> &src) const
    {
      AssertDimension(src.size(), columns_.size());
      dst.reinit(n_modes_);
      for (unsigned int r = 0; r < columns_.size(); ++r)
        for (const auto &[k, v] : columns_[r])
          dst(k) += v * src(r);
    }


    void
    CoarseProblem::Tvmult(dealii::Vector<double>       &dst,
                          const dealii::Vector<double> &src) const
    {
      AssertDimension(src.size(), n_modes_);
      dst.reinit(columns_.size());
      for (unsigned int r = 0; r < columns_.size(); ++r)
      {
        double sum = 0;
        for (const auto &[k, v] : columns_[r])
          sum += v * src(k);
        dst(r) = sum;
      }
    }


    void
    CoarseProblem::add_columns(dealii::Vector<double>          &dst,
                               const std::vector<unsigned int> &rows,
                               const double                    *src) const
    {
      AssertDimension(dst.size(), n_modes_);
      for (unsigned int l = 0; l < rows.size(); ++l)
        for (const auto &[k, v] : columns_[rows[l]])
          dst(k) += v * src[l];
    }


    void
    CoarseProblem::Tvmult_columns(const dealii::Vector<double>    &src,
                                  const std::vector<unsigned int> &rows,
                                  double                          *dst) const
    {
      AssertDimension(src.size(), n_modes_);
      for (unsigned int l = 0; l < rows.size(); ++l)
      {
        double sum = 0;
        for (const auto &[k, v] : columns_[rows[l]])
          sum += v * src(k);
        dst[l] = sum;
      }
    }


    void
    CoarseProblem::orthonormalize(dealii::Vector<double> &x) const
    {
      factor_->solve_lower(x);
    }


    void
    CoarseProblem::orthonormalize_transpose(dealii::Vector<double> &x) const
    {
      factor_->solve_upper(x);
    }


    bool
    CoarseProblem::least_squares(const std::function<bool(unsigned int)> &in_A,
                                 const dealii::Vector<double>            &r,
                                 dealii::Vector<double> &alpha) const
    {
      AssertDimension(r.size(), columns_.size());
      dealii::Vector<double> rhs(n_modes_);
      for (unsigned int c = 0; c < columns_.size(); ++c)
        if (in_A(c))
          for (const auto &[k, v] : columns_[c])
            rhs(k) += v * r(c);

      dealii::SparsityPattern      pattern;
      dealii::SparseMatrix<double> normal;
      fem::CholmodSolver           solver;
      bool                         determined = true;
      assemble_normal_matrix(in_A, pattern, normal);
      if (!factorize(solver, normal))
      {
        // a floating body that nothing holds yet (an early Coulomb
        // iterate, no active contact): the shift picks, of the
        // least-squares solutions, one with about no kernel component
        determined     = false;
        double largest = 0;
        for (unsigned int k = 0; k < n_modes_; ++k)
          largest = std::max(largest, normal.diag_element(k));
        for (unsigned int k = 0; k < n_modes_; ++k)
          normal.diag_element(k) += 1e-12 * (largest > 0 ? largest : 1.);
        solver.initialize(normal);
      }
      solver.solve(alpha, rhs);
      return determined;
    }


    std::size_t
    CoarseProblem::n_nonzeros() const
    {
      return ggt_.n_nonzero_elements();
    }


    double
    CoarseProblem::n_factor_nonzeros() const
    {
      return factor_->statistics().factor_nonzeros;
    }


    double
    CoarseProblem::setup_time() const
    {
      return setup_time_;
    }


    void
    CoarseProblem::assemble_normal_matrix(
      const std::function<bool(unsigned int)> &in_A,
      dealii::SparsityPattern                 &pattern,
      dealii::SparseMatrix<double>            &matrix) const
    {
      dealii::DynamicSparsityPattern dynamic(n_modes_);
      for (unsigned int k = 0; k < n_modes_; ++k)
        dynamic.add(k, k);
      for (unsigned int c = 0; c < columns_.size(); ++c)
        if (in_A(c))
          for (const auto &[k, v] : columns_[c])
            for (const auto &[l, w] : columns_[c])
              dynamic.add(k, l);
      pattern.copy_from(dynamic);
      matrix.reinit(pattern);
      for (unsigned int c = 0; c < columns_.size(); ++c)
        if (in_A(c))
          for (const auto &[k, v] : columns_[c])
            for (const auto &[l, w] : columns_[c])
              matrix.add(k, l, v * w);
    }
  } // namespace decomposition
} // namespace dualcontact
