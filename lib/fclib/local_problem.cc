#include <deal.II/base/exceptions.h>

#include <fclib/local_problem.h>

#include <cmath>

namespace dualcontact
{
  namespace fclib
  {
    LocalProblem::LocalProblem(const unsigned int            spacedim,
                               const Triplets               &W,
                               const dealii::Vector<double> &q,
                               const std::vector<double>    &mu,
                               const std::string            &title,
                               const Storage                 storage)
        : ContactList(spacedim, mu, title)
        , q_(q)
    {
      const unsigned int n = n_contact_unknowns();
      AssertThrow(W.n_rows() == n && W.n_cols() == n && q.size() == n,
                  dealii::ExcMessage(
                    "FCLIB local problem: W is " + std::to_string(W.n_rows()) +
                    " x " + std::to_string(W.n_cols()) + " and q has " +
                    std::to_string(q.size()) + " entries, but " +
                    std::to_string(mu.size()) + " contacts in dimension " +
                    std::to_string(spacedim) + " need " + std::to_string(n)));
      for (const double v : q)
        AssertThrow(std::isfinite(v),
                    dealii::ExcMessage("FCLIB problem: non-finite entry in q"));
      W_ = DelassusOperator(W, storage);
    }


    unsigned int
    LocalProblem::size() const
    {
      return q_.size();
    }


    const dealii::SparseMatrix<double> &
    LocalProblem::W() const
    {
      return W_.matrix();
    }


    const DelassusOperator &
    LocalProblem::delassus() const
    {
      return W_;
    }


    const dealii::Vector<double> &
    LocalProblem::q() const
    {
      return q_;
    }


    void
    LocalProblem::velocity(dealii::Vector<double>       &u,
                           const dealii::Vector<double> &r) const
    {
      W_.vmult(u, r);
      u += q_;
    }
  } // namespace fclib
} // namespace dualcontact
