#include <deal.II/base/exceptions.h>

#include <decomposition/multiplier_exchange.h>

#include <algorithm>
#include <map>

namespace dualcontact
{
  namespace decomposition
  {
    using namespace dealii;

    namespace
    {
      // message tags of the two directions (the same pairs of processes
      // exchange in both)
      constexpr int import_tag = 4711;
      constexpr int export_tag = 4712;
    } // namespace


    MultiplierExchange::MultiplierExchange(
      const IndexSet                  &owned,
      const std::vector<unsigned int> &relevant,
      const std::vector<unsigned int> &relevant_owner,
      const MPI_Comm                   communicator)
        : communicator_(communicator)
        , owned_(owned)
        , relevant_(relevant)
    {
      AssertDimension(relevant.size(), relevant_owner.size());
      Assert(std::is_sorted(relevant.begin(), relevant.end()),
             ExcInternalError());
      const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
      owned_position_.assign(relevant_.size(), -1);
      // the ghost rows by owner; each owner learns which of its rows this
      // process reads
      std::map<unsigned int, std::vector<unsigned int>> requests;
      std::map<unsigned int, std::vector<unsigned int>> ghosts;
      for (unsigned int i = 0; i < relevant_.size(); ++i)
        if (relevant_owner[i] == rank)
        {
          Assert(owned_.is_element(relevant_[i]), ExcInternalError());
          owned_position_[i] = owned_.index_within_set(relevant_[i]);
        }
        else
        {
          requests[relevant_owner[i]].push_back(relevant_[i]);
          ghosts[relevant_owner[i]].push_back(i);
        }
      const std::map<unsigned int, std::vector<unsigned int>> asked =
        Utilities::MPI::some_to_some(communicator_, requests);

      std::map<unsigned int, Neighbour> neighbours;
      for (const auto &[p, positions] : ghosts)
      {
        neighbours[p].rank   = p;
        neighbours[p].ghosts = positions;
      }
      for (const auto &[p, rows] : asked)
      {
        neighbours[p].rank = p;
        for (const unsigned int row : rows)
        {
          AssertThrow(owned_.is_element(row),
                      ExcMessage("MultiplierExchange: process " +
                                 std::to_string(p) + " reads row " +
                                 std::to_string(row) +
                                 ", which this process does not own."));
          neighbours[p].owned.push_back(owned_.index_within_set(row));
        }
      }
      for (auto &[p, neighbour] : neighbours)
        neighbours_.push_back(std::move(neighbour));
    }


    unsigned int
    MultiplierExchange::relevant_index(const unsigned int row) const
    {
      const auto it = std::lower_bound(relevant_.begin(), relevant_.end(), row);
      Assert(it != relevant_.end() && *it == row, ExcInternalError());
      return it - relevant_.begin();
    }


    void
    MultiplierExchange::import(const DistributedVector &src,
                               std::vector<double>     &values) const
    {
      AssertDimension(src.locally_owned_size(), owned_.n_elements());
      values.assign(relevant_.size(), 0.);
      const double *own = src.begin();
      for (unsigned int i = 0; i < relevant_.size(); ++i)
        if (owned_position_[i] >= 0)
          values[i] = own[owned_position_[i]];

      std::vector<std::vector<double>> sent(neighbours_.size()),
        received(neighbours_.size());
      for (unsigned int n = 0; n < neighbours_.size(); ++n)
      {
        for (const unsigned int l : neighbours_[n].owned)
          sent[n].push_back(own[l]);
        received[n].resize(neighbours_[n].ghosts.size());
      }
      swap_with_neighbours(sent, received, import_tag);
      for (unsigned int n = 0; n < neighbours_.size(); ++n)
        for (unsigned int g = 0; g < neighbours_[n].ghosts.size(); ++g)
          values[neighbours_[n].ghosts[g]] = received[n][g];
    }


    void
    MultiplierExchange::export_add(const std::vector<double> &values,
                                   DistributedVector         &dst) const
    {
      AssertDimension(values.size(), relevant_.size());
      AssertDimension(dst.locally_owned_size(), owned_.n_elements());
      double *own = dst.begin();
      std::fill(own, own + owned_.n_elements(), 0.);
      for (unsigned int i = 0; i < relevant_.size(); ++i)
        if (owned_position_[i] >= 0)
          own[owned_position_[i]] = values[i];

      // the reverse of import(): the ghosts' contributions go to their
      // owners, which add them up in neighbour order (the same order on
      // every run with the same processes)
      std::vector<std::vector<double>> sent(neighbours_.size()),
        received(neighbours_.size());
      for (unsigned int n = 0; n < neighbours_.size(); ++n)
      {
        for (const unsigned int i : neighbours_[n].ghosts)
          sent[n].push_back(values[i]);
        received[n].resize(neighbours_[n].owned.size());
      }
      swap_with_neighbours(sent, received, export_tag);
      for (unsigned int n = 0; n < neighbours_.size(); ++n)
        for (unsigned int k = 0; k < neighbours_[n].owned.size(); ++k)
          own[neighbours_[n].owned[k]] += received[n][k];
    }


    void
    MultiplierExchange::swap_with_neighbours(
      const std::vector<std::vector<double>> &sent,
      std::vector<std::vector<double>>       &received,
      const int                               tag) const
    {
      std::vector<MPI_Request> requests;
      requests.reserve(2 * neighbours_.size());
      for (unsigned int n = 0; n < neighbours_.size(); ++n)
      {
        if (!received[n].empty())
        {
          requests.emplace_back();
          const int ierr = MPI_Irecv(received[n].data(),
                                     received[n].size(),
                                     MPI_DOUBLE,
                                     neighbours_[n].rank,
                                     tag,
                                     communicator_,
                                     &requests.back());
          AssertThrowMPI(ierr);
        }
        if (!sent[n].empty())
        {
          requests.emplace_back();
          const int ierr = MPI_Isend(sent[n].data(),
                                     sent[n].size(),
                                     MPI_DOUBLE,
                                     neighbours_[n].rank,
                                     tag,
                                     communicator_,
                                     &requests.back());
          AssertThrowMPI(ierr);
        }
      }
      const int ierr =
        MPI_Waitall(requests.size(), requests.data(), MPI_STATUSES_IGNORE);
      AssertThrowMPI(ierr);
    }
  } // namespace decomposition
} // namespace dualcontact
