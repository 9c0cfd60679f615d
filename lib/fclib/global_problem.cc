#include <deal.II/base/exceptions.h>

#include <fclib/global_problem.h>
#include <fem/cholmod_solver.h>
#include <fem/umfpack_solver.h>

#include <cmath>

namespace dualcontact
{
  namespace fclib
  {
    GlobalProblem::GlobalProblem(const unsigned int            spacedim,
                                 Triplets                      M,
                                 const Triplets               &H,
                                 const dealii::Vector<double> &f,
                                 const dealii::Vector<double> &w,
                                 const std::vector<double>    &mu,
                                 const std::string            &title)
        : ContactList(spacedim, mu, title)
        , f_(f)
        , w_(w)
    {
      const unsigned int n = M.n_rows(), m = n_contact_unknowns();
      AssertThrow(
        M.n_cols() == n && H.n_rows() == n && H.n_cols() == m &&
          f.size() == n && w.size() == m,
        dealii::ExcMessage(
          "FCLIB global problem: inconsistent sizes (M " +
          std::to_string(M.n_rows()) + " x " + std::to_string(M.n_cols()) +
          ", H " + std::to_string(H.n_rows()) + " x " +
          std::to_string(H.n_cols()) + ", f " + std::to_string(f.size()) +
          ", w " + std::to_string(w.size()) + ", " + std::to_string(mu.size()) +
          " contacts in dimension " + std::to_string(spacedim) + ")"));
      M_upper_ = M.upper_triangle_only();
      if (M_upper_)
        M.symmetrize_from_upper();
      M_ = OwnedSparseMatrix(M);
      H_ = OwnedSparseMatrix(H);
    }


    GlobalProblem::~GlobalProblem() = default;


    unsigned int
    GlobalProblem::n_dofs() const
    {
      return f_.size();
    }


    const dealii::SparseMatrix<double> &
    GlobalProblem::M() const
    {
      return M_.matrix;
    }


    const dealii::SparseMatrix<double> &
    GlobalProblem::H() const
    {
      return H_.matrix;
    }


    const dealii::Vector<double> &
    GlobalProblem::f() const
    {
      return f_;
    }


    const dealii::Vector<double> &
    GlobalProblem::w() const
    {
      return w_;
    }


    bool
    GlobalProblem::M_was_upper_triangle() const
    {
      return M_upper_;
    }


    std::string
    GlobalProblem::factorization_name() const
    {
      return factorization_ ? factorization_->name() : "";
    }


    void
    GlobalProblem::factorize() const
    {
      if (factorization_)
        return;
      try
      {
        auto cholmod = std::make_unique<fem::CholmodSolver>();
        cholmod->initialize(M_.matrix);
        factorization_ = std::move(cholmod);
      }
      catch (const std::exception &)
      {
        // not positive definite (or CHOLMOD failed otherwise): sparse LU
        auto umfpack = std::make_unique<fem::UmfpackSolver>();
        umfpack->initialize(M_.matrix);
        factorization_ = std::move(umfpack);
      }
    }


    LocalProblem
    GlobalProblem::reduce_to_local(const Storage storage) const
    {
      factorize();
      const unsigned int                  n = n_dofs(), m = H_.matrix.n();
      const dealii::SparseMatrix<double> &H = H_.matrix;

      // columns of H: H is stored by rows; gather column j's entries
      std::vector<std::vector<std::pair<unsigned int, double>>> columns(m);
      for (unsigned int i = 0; i < n; ++i)
        for (auto it = H.begin(i); it != H.end(i); ++it)
          if (it->value() != 0.)
            columns[it->column()].emplace_back(i, it->value());

      Triplets               W(m, m);
      dealii::Vector<double> h(n), x(n), column(m);
      for (unsigned int j = 0; j < m; ++j)
      {
        if (columns[j].empty())
          continue;
        h = 0;
        for (const auto &[i, value] : columns[j])
          h(i) = value;
        factorization_->solve(x, h);
        H.Tvmult(column, x);
        for (unsigned int i = 0; i < m; ++i)
          if (column(i) != 0.)
            W.add(i, j, column(i));
      }
      dealii::Vector<double> q(m);
      factorization_->solve(x, f_);
      H.Tvmult(q, x);
      q += w_;
      return LocalProblem(spacedim(), W, q, mu(), title(), storage);
    }


    void
    GlobalProblem::velocity(dealii::Vector<double>       &v,
                            const dealii::Vector<double> &r) const
    {
      factorize();
      dealii::Vector<double> rhs(f_);
      H_.matrix.vmult_add(rhs, r);
      v.reinit(n_dofs());
      factorization_->solve(v, rhs);
    }
  } // namespace fclib
} // namespace dualcontact
