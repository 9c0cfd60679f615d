#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <decomposition/multiplier_ownership.h>

#include <algorithm>
#include <limits>

namespace dualcontact
{
  namespace decomposition
  {
    using namespace dealii;

    namespace
    {
      constexpr unsigned int invalid = std::numeric_limits<unsigned int>::max();
    }


    template <int dim>
    MultiplierOwnership<dim>::MultiplierOwnership(
      const ConstraintRows<dim>                    &rows,
      const std::vector<unsigned int>              &subdomain_owner,
      const std::vector<unsigned int>              &owned_subdomains,
      const std::vector<std::vector<unsigned int>> &node_rows,
      const MPI_Comm                                communicator)
    {
      const unsigned int n_rows = rows.n_rows();
      const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
      std::vector<unsigned int> row_owner =
        choose_subdomains(rows, owned_subdomains, node_rows, communicator);
      for (unsigned int &owner : row_owner)
        owner = owner == invalid ? 0 : subdomain_owner[owner];

      std::vector<unsigned int> owned_rows;
      for (unsigned int r = 0; r < n_rows; ++r)
        if (row_owner[r] == rank)
          owned_rows.push_back(r);
      layout_ =
        contact::MultiplierLayout(n_rows, std::move(owned_rows), communicator);
      relevant_index_.assign(subdomain_owner.size(), {});
      set_up_exchange(rows, owned_subdomains, row_owner, communicator);

      nodes_per_process_.assign(Utilities::MPI::n_mpi_processes(communicator),
                                0);
      for (const std::vector<unsigned int> &node : node_rows)
        ++nodes_per_process_[row_owner[node[0]]];
    }


    template <int dim>
    std::vector<unsigned int>
    MultiplierOwnership<dim>::choose_subdomains(
      const ConstraintRows<dim>                    &rows,
      const std::vector<unsigned int>              &owned_subdomains,
      const std::vector<std::vector<unsigned int>> &node_rows,
      const MPI_Comm                                communicator)
    {
      const unsigned int n_rows = rows.n_rows();
      // the lowest and the highest subdomain whose B_s touches each row
      // (over all processes: each knows its own subdomains' entries; highest
      // is read only where lowest says some subdomain touches the row)
      std::vector<unsigned int> lowest(n_rows, invalid), highest(n_rows, 0);
      for (const unsigned int s : owned_subdomains)
        for (const auto &entry : rows.entries(s))
        {
          lowest[entry.row]  = std::min(lowest[entry.row], s);
          highest[entry.row] = std::max(highest[entry.row], s);
        }
      if (Utilities::MPI::n_mpi_processes(communicator) > 1)
        for (const auto &[v, op] : {std::make_pair(&lowest, MPI_MIN),
                                    std::make_pair(&highest, MPI_MAX)})
        {
          const int ierr = MPI_Allreduce(
            MPI_IN_PLACE, v->data(), v->size(), MPI_UNSIGNED, op, communicator);
          AssertThrowMPI(ierr);
        }
      std::vector<unsigned int> chosen(n_rows, invalid);
      for (unsigned int r = 0; r < n_rows; ++r)
        if (lowest[r] != invalid)
          chosen[r] = r % 2 == 0 ? lowest[r] : highest[r];
      for (const std::vector<unsigned int> &node : node_rows)
      {
        unsigned int m = invalid;
        for (const unsigned int r : node)
          m = std::min(m, lowest[r]);
        for (const unsigned int r : node)
          chosen[r] = m;
      }
      return chosen;
    }


    template <int dim>
    void
    MultiplierOwnership<dim>::set_up_exchange(
      const ConstraintRows<dim>       &rows,
      const std::vector<unsigned int> &owned_subdomains,
      const std::vector<unsigned int> &row_owner,
      const MPI_Comm                   communicator)
    {
      std::vector<unsigned int> relevant = layout_.owned_rows();
      for (const unsigned int s : owned_subdomains)
        for (const auto &entry : rows.entries(s))
          relevant.push_back(entry.row);
      std::sort(relevant.begin(), relevant.end());
      relevant.erase(std::unique(relevant.begin(), relevant.end()),
                     relevant.end());
      std::vector<unsigned int> relevant_owner(relevant.size());
      for (unsigned int i = 0; i < relevant.size(); ++i)
        relevant_owner[i] = row_owner[relevant[i]];
      exchange_ = std::make_unique<MultiplierExchange>(layout_.locally_owned(),
                                                       relevant,
                                                       relevant_owner,
                                                       communicator);
      for (const unsigned int s : owned_subdomains)
        for (const auto &entry : rows.entries(s))
          relevant_index_[s].push_back(exchange_->relevant_index(entry.row));
    }


    template <int dim>
    const contact::MultiplierLayout &
    MultiplierOwnership<dim>::layout() const
    {
      return layout_;
    }


    template <int dim>
    const MultiplierExchange &
    MultiplierOwnership<dim>::exchange() const
    {
      return *exchange_;
    }


    template <int dim>
    const std::vector<std::vector<unsigned int>> &
    MultiplierOwnership<dim>::relevant_index() const
    {
      return relevant_index_;
    }


    template <int dim>
    const std::vector<unsigned int> &
    MultiplierOwnership<dim>::nodes_per_process() const
    {
      return nodes_per_process_;
    }


    template class MultiplierOwnership<2>;
    template class MultiplierOwnership<3>;
  } // namespace decomposition
} // namespace dualcontact
