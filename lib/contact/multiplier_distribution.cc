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
      if (!distributed_)
      {
        // one process owns all rows, in order (recover() runs the loop of
        // the distributed recovery over them)
        owned_nodes_.resize(n_nodes);
        std::iota(owned_nodes_.begin(), owned_nodes_.end(), 0u);
        owned_frictional_.resize(frictional_nodes.size());
        std::iota(owned_frictional_.begin(), owned_frictional_.end(), 0u);
        layout_ = MultiplierLayout(m);
        nodes_per_process_.assign(1, n_nodes);
        multipliers_per_process_.assign(1, m);
        return;
      }
      const unsigned int n_processes =
        Utilities::MPI::job_supports_mpi() ?
          Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) :
          1;
      const MPI_Comm     communicator = MPI_COMM_WORLD;
      const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);

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
      Utilities::MPI::sum(mine, communicator, claims);
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

      std::vector<unsigned int> owned_rows = owned_nodes_;
      for (const unsigned int j : owned_frictional_)
        for (unsigned int k = 0; k < dim - 1; ++k)
          owned_rows.push_back(n_nodes + (dim - 1) * j + k);
      layout_ = MultiplierLayout(m, std::move(owned_rows), communicator);
      nodes_per_process_ = Utilities::MPI::all_gather(
        communicator, static_cast<unsigned int>(owned_nodes_.size()));
      multipliers_per_process_ = Utilities::MPI::all_gather(
        communicator, static_cast<unsigned int>(layout_.owned_rows().size()));
    }


    bool
    MultiplierDistribution::is_distributed() const
    {
      return distributed_;
    }


    MPI_Comm
    MultiplierDistribution::communicator() const
    {
      return layout_.communicator();
    }


    const std::vector<unsigned int> &
    MultiplierDistribution::owned_rows() const
    {
      return layout_.owned_rows();
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


    const MultiplierLayout &
    MultiplierDistribution::layout() const
    {
      return layout_;
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
