#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <contact/multiplier_distribution.h>

#include <algorithm>
#include <numeric>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    MultiplierDistribution::MultiplierDistribution(
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const ContactDiscretization<dim>                 &contact,
      const std::vector<unsigned int>                  &frictional_nodes,
      const std::vector<int>                           &frictional_index,
      const bool                                        distributed)
        : distributed_(distributed)
    {
      const unsigned int n_nodes = contact.n_nodes();
      const unsigned int m = n_nodes + (dim - 1) * frictional_nodes.size();
      n_multipliers_       = m;
      if (!distributed_)
      {
        // one process owns all rows, in order (recover() runs the loop of
        // the distributed recovery over them)
        owned_nodes_.resize(n_nodes);
        std::iota(owned_nodes_.begin(), owned_nodes_.end(), 0u);
        owned_frictional_.resize(frictional_nodes.size());
        std::iota(owned_frictional_.begin(), owned_frictional_.end(), 0u);
        owned_rows_.resize(m);
        std::iota(owned_rows_.begin(), owned_rows_.end(), 0u);
        owned_multipliers_ = complete_index_set(m);
        nodes_per_process_.assign(1, n_nodes);
        multipliers_per_process_.assign(1, m);
        return;
      }
      const unsigned int n_processes =
        Utilities::MPI::job_supports_mpi() ?
          Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) :
          1;
      communicator_           = MPI_COMM_WORLD;
      const unsigned int rank = Utilities::MPI::this_mpi_process(communicator_);

      // a node belongs to the process owning its first slave dof, if the
      // bodies are partitioned (every node claimed exactly once); else
      // (bodies on plain triangulations: every process owns all dofs) the
      // nodes are split evenly in their order
      std::vector<unsigned int> mine(n_nodes, 0), claims(n_nodes, 0);
      for (unsigned int i = 0; i < n_nodes; ++i)
      {
        const ContactNode<dim> &node = contact.nodes()[i];
        const unsigned int      b    = contact.pairs()[node.pair].slave_body;
        mine[i] = bodies[b]->dof_handler().locally_owned_dofs().is_element(
                    node.dofs[0]) ?
                    1 :
                    0;
      }
      Utilities::MPI::sum(mine, communicator_, claims);
      const bool partitioned =
        std::all_of(claims.begin(),
                    claims.end(),
                    [](const unsigned int c) { return c == 1; });
      for (unsigned int i = 0; i < n_nodes; ++i)
      {
        const bool owned =
          partitioned ?
            mine[i] == 1 :
            (i >= static_cast<unsigned long>(n_nodes) * rank / n_processes &&
             i <
               static_cast<unsigned long>(n_nodes) * (rank + 1) / n_processes);
        if (!owned)
          continue;
        owned_nodes_.push_back(i);
        if (frictional_index[i] >= 0)
          owned_frictional_.push_back(frictional_index[i]);
      }

      owned_multipliers_ = IndexSet(m);
      for (const unsigned int i : owned_nodes_)
        owned_multipliers_.add_index(i);
      for (const unsigned int j : owned_frictional_)
        owned_multipliers_.add_range(n_nodes + (dim - 1) * j,
                                     n_nodes + (dim - 1) * (j + 1));
      owned_multipliers_.compress();
      for (const auto r : owned_multipliers_)
        owned_rows_.push_back(r);
      nodes_per_process_ = Utilities::MPI::all_gather(
        communicator_, static_cast<unsigned int>(owned_nodes_.size()));
      multipliers_per_process_ = Utilities::MPI::all_gather(
        communicator_, static_cast<unsigned int>(owned_rows_.size()));
    }


    bool
    MultiplierDistribution::is_distributed() const
    {
      return distributed_;
    }


    MPI_Comm
    MultiplierDistribution::communicator() const
    {
      return communicator_;
    }


    const IndexSet &
    MultiplierDistribution::locally_owned() const
    {
      return owned_multipliers_;
    }


    const std::vector<unsigned int> &
    MultiplierDistribution::owned_rows() const
    {
      return owned_rows_;
    }


    const std::vector<unsigned int> &
    MultiplierDistribution::owned_nodes() const
    {
      return owned_nodes_;
    }


    const std::vector<unsigned int> &
    MultiplierDistribution::owned_frictional() const
    {
      return owned_frictional_;
    }


    const std::vector<unsigned int> &
    MultiplierDistribution::nodes_per_process() const
    {
      return nodes_per_process_;
    }


    const std::vector<unsigned int> &
    MultiplierDistribution::multipliers_per_process() const
    {
      return multipliers_per_process_;
    }


    void
    MultiplierDistribution::initialize(DistributedVector &lambda) const
    {
      AssertThrow(distributed_,
                  ExcMessage("DualProblem: distributed multipliers asked "
                             "for a replicated dual problem."));
      lambda.reinit(owned_multipliers_, communicator_);
    }


    void
    MultiplierDistribution::gather(const DistributedVector &lambda,
                                   Vector<double>          &whole) const
    {
      AssertDimension(lambda.locally_owned_size(), owned_rows_.size());
      whole.reinit(n_multipliers_);
      for (unsigned int k = 0; k < owned_rows_.size(); ++k)
        whole(owned_rows_[k]) = lambda.begin()[k];
      // each entry is owned by one process: the sum is the entry itself
      const int ierr = MPI_Allreduce(MPI_IN_PLACE,
                                     whole.begin(),
                                     whole.size(),
                                     MPI_DOUBLE,
                                     MPI_SUM,
                                     communicator_);
      AssertThrowMPI(ierr);
    }


    template MultiplierDistribution::MultiplierDistribution(
      const std::vector<const fem::ElasticBody<2> *> &,
      const ContactDiscretization<2> &,
      const std::vector<unsigned int> &,
      const std::vector<int> &,
      const bool);
    template MultiplierDistribution::MultiplierDistribution(
      const std::vector<const fem::ElasticBody<3> *> &,
      const ContactDiscretization<3> &,
      const std::vector<unsigned int> &,
      const std::vector<int> &,
      const bool);
  } // namespace contact
} // namespace dualcontact
