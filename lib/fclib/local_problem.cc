#include <deal.II/base/exceptions.h>

#include <fclib/local_problem.h>

#include <algorithm>
#include <cmath>

namespace dualcontact
{
  namespace fclib
  {
    LocalProblem::LocalProblem(const unsigned int            spacedim,
                               const Triplets               &W,
                               const dealii::Vector<double> &q,
                               const std::vector<double>    &mu,
                               const std::string            &title)
        : spacedim_(spacedim)
        , W_(W)
        , q_(q)
        , mu_(mu)
        , title_(title)
    {
      AssertThrow(spacedim == 2 || spacedim == 3,
                  dealii::ExcMessage("FCLIB problem: space dimension " +
                                     std::to_string(spacedim) +
                                     ", expected 2 or 3"));
      const unsigned int n = spacedim * mu.size();
      AssertThrow(W.n_rows() == n && W.n_cols() == n && q.size() == n,
                  dealii::ExcMessage(
                    "FCLIB local problem: W is " + std::to_string(W.n_rows()) +
                    " x " + std::to_string(W.n_cols()) + " and q has " +
                    std::to_string(q.size()) + " entries, but " +
                    std::to_string(mu.size()) + " contacts in dimension " +
                    std::to_string(spacedim) + " need " + std::to_string(n)));
      for (const double m : mu)
        AssertThrow(m >= 0 && std::isfinite(m),
                    dealii::ExcMessage(
                      "FCLIB problem: negative or non-finite friction "
                      "coefficient mu = " +
                      std::to_string(m)));
      for (const double v : q)
        AssertThrow(std::isfinite(v),
                    dealii::ExcMessage("FCLIB problem: non-finite entry in q"));
      work_.reinit(n);
    }


    unsigned int
    LocalProblem::spacedim() const
    {
      return spacedim_;
    }


    unsigned int
    LocalProblem::n_contacts() const
    {
      return mu_.size();
    }


    unsigned int
    LocalProblem::size() const
    {
      return q_.size();
    }


    const dealii::SparseMatrix<double> &
    LocalProblem::W() const
    {
      return W_.matrix;
    }


    const dealii::Vector<double> &
    LocalProblem::q() const
    {
      return q_;
    }


    const std::vector<double> &
    LocalProblem::mu() const
    {
      return mu_;
    }


    const std::string &
    LocalProblem::title() const
    {
      return title_;
    }


    void
    LocalProblem::velocity(dealii::Vector<double>       &u,
                           const dealii::Vector<double> &r) const
    {
      u.reinit(size());
      W_.matrix.vmult(u, r);
      u += q_;
    }


    void
    LocalProblem::symmetric_vmult(dealii::Vector<double>       &dst,
                                  const dealii::Vector<double> &src) const
    {
      dst.reinit(size(), true);
      W_.matrix.vmult(dst, src);
      W_.matrix.Tvmult(work_, src);
      dst += work_;
      dst *= 0.5;
    }


    void
    LocalProblem::antisymmetric_vmult(dealii::Vector<double>       &dst,
                                      const dealii::Vector<double> &src) const
    {
      dst.reinit(size(), true);
      W_.matrix.vmult(dst, src);
      W_.matrix.Tvmult(work_, src);
      dst -= work_;
      dst *= 0.5;
    }


    double
    LocalProblem::asymmetry() const
    {
      const dealii::SparseMatrix<double> &W       = W_.matrix;
      double                              largest = 0, difference = 0;
      for (unsigned int i = 0; i < W.m(); ++i)
        for (auto it = W.begin(i); it != W.end(i); ++it)
        {
          largest = std::max(largest, std::abs(it->value()));
          difference =
            std::max(difference, std::abs(it->value() - W.el(it->column(), i)));
        }
      return largest > 0 ? difference / largest : 0.;
    }
  } // namespace fclib
} // namespace dualcontact
