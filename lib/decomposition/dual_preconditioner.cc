#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <decomposition/dual_preconditioner.h>
#include <util/machine.h>

#include <algorithm>

namespace dualcontact
{
  namespace decomposition
  {
    template <int dim>
    DualPreconditioner<dim>::DualPreconditioner(
      const Kind                                          kind,
      const ConstraintRows<dim>                          &rows,
      const std::vector<std::unique_ptr<Subdomain<dim>>> &subdomains,
      const std::vector<unsigned int>                    &owned,
      const unsigned int                                  n_multipliers,
      const MPI_Comm                                      communicator,
      const std::function<std::unique_ptr<fem::StiffnessSolver>()> &make_solver,
      BetweenB                                                      between_B)
        : kind_(kind)
        , rows_(rows)
        , subdomains_(subdomains)
        , owned_(owned)
        , between_B_(std::move(between_B))
    {
      build_scaling(n_multipliers, communicator);
      if (kind == Kind::dirichlet)
        build_schur_complements(make_solver);
    }


    template <int dim>
    void
    DualPreconditioner<dim>::build_scaling(const unsigned int n_multipliers,
                                           const MPI_Comm     communicator)
    {
      using Entry = typename ConstraintRows<dim>::Entry;
      // (row, row, value) of B_s B_s' for the owned subdomains: the rows
      // that share a local dof, grouped by subdomain and dof
      std::vector<double> triples;
      for (const unsigned int s : owned_)
      {
        std::vector<Entry> by_dof = rows_.entries(s);
        std::sort(by_dof.begin(),
                  by_dof.end(),
                  [](const Entry &a, const Entry &b)
                  { return a.local < b.local; });
        for (std::size_t begin = 0, end; begin < by_dof.size(); begin = end)
        {
          for (end = begin;
               end < by_dof.size() && by_dof[end].local == by_dof[begin].local;
               ++end)
            ;
          for (std::size_t i = begin; i < end; ++i)
            for (std::size_t j = begin; j < end; ++j)
              triples.insert(triples.end(),
                             {static_cast<double>(by_dof[i].row),
                              static_cast<double>(by_dof[j].row),
                              by_dof[i].value * by_dof[j].value});
        }
      }
      if (dealii::Utilities::MPI::job_supports_mpi() &&
          dealii::Utilities::MPI::n_mpi_processes(communicator) > 1)
        triples = util::concatenate_over_processes(triples, communicator);
      scaling_ = std::make_unique<MultiplierScaling>(n_multipliers, triples);
    }


    template <int dim>
    void
    DualPreconditioner<dim>::build_schur_complements(
      const std::function<std::unique_ptr<fem::StiffnessSolver>()> &make_solver)
    {
      schur_.resize(subdomains_.size());
      for (const unsigned int s : owned_)
      {
        // the interface: every local dof an entry of B_s touches
        std::vector<unsigned int> interface;
        interface.reserve(rows_.entries(s).size());
        for (const auto &entry : rows_.entries(s))
          interface.push_back(entry.local);
        std::sort(interface.begin(), interface.end());
        interface.erase(std::unique(interface.begin(), interface.end()),
                        interface.end());
        schur_[s] = std::make_unique<InterfaceSchurComplement>(
          subdomains_[s]->stiffness_matrix(),
          interface,
          make_solver(),
          subdomains_[s]->name());
      }
    }


    template <int dim>
    void
    DualPreconditioner<dim>::vmult(VectorType &dst, const VectorType &src) const
    {
      VectorType y = src;
      scaling_->apply(y);
      if (kind_ == Kind::dirichlet)
        between_B_(dst,
                   y,
                   [this](const unsigned int s,
                          VectorType        &out,
                          const VectorType  &v) { schur_[s]->vmult(out, v); });
      else
        between_B_(dst,
                   y,
                   [this](const unsigned int s,
                          VectorType        &out,
                          const VectorType  &v)
                   { subdomains_[s]->stiffness_matrix().vmult(out, v); });
      scaling_->apply(dst);
    }


    template <int dim>
    typename DualPreconditioner<dim>::Kind
    DualPreconditioner<dim>::kind() const
    {
      return kind_;
    }


    template class DualPreconditioner<2>;
    template class DualPreconditioner<3>;
  } // namespace decomposition
} // namespace dualcontact
