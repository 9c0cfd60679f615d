#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <contact/contact_discretization.h>
#include <contact/multiplier_layout.h>
#include <fem/elastic_body.h>

#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * Which process owns which multipliers of the undecomposed dual (see
     * DualProblem, "Distribution"): every contact node, with its normal
     * and tangential multipliers, belongs to the process owning the node's
     * first slave dof, or, when the bodies are not partitioned (every
     * process owns every dof), to the processes in an even split of the
     * nodes in order.  Replicated (one process, or `set QP vectors =
     * replicated'): this process owns every multiplier, in order.
     */
    class MultiplierDistribution
    {
    public:
      using DistributedVector = dealii::TrilinosWrappers::MPI::Vector;

      /**
       * Distributed if @p distributed (collective then: the ownership is
       * decided with the other processes of MPI_COMM_WORLD).
       * @p frictional_nodes and @p frictional_index as DualFormulation's.
       */
      template <int dim>
      MultiplierDistribution(
        const std::vector<const fem::ElasticBody<dim> *> &bodies,
        const ContactDiscretization<dim>                 &contact,
        const std::vector<unsigned int>                  &frictional_nodes,
        const std::vector<int>                           &frictional_index,
        const bool                                        distributed);

      bool
      is_distributed() const;
      /** MPI_COMM_WORLD if distributed, else MPI_COMM_SELF. */
      MPI_Comm
      communicator() const;
      /** The owned multipliers' global indices, in local order. */
      const std::vector<unsigned int> &
      owned_rows() const;
      /** The owned contact nodes, sorted. */
      const std::vector<unsigned int> &
      owned_nodes() const;
      /** The owned frictional nodes (indices j into the frictional
       *  nodes), sorted. */
      const std::vector<unsigned int> &
      owned_frictional() const;
      /** Owned contact nodes per process (one entry if replicated). */
      const std::vector<unsigned int> &
      nodes_per_process() const;
      /** Owned multipliers per process (one entry if replicated). */
      const std::vector<unsigned int> &
      multipliers_per_process() const;

      /** The owned rows and the moves between the whole vector and the
       *  owned part (MultiplierLayout::initialize() and gather()). */
      const MultiplierLayout &
      layout() const;

    private:
      bool                      distributed_ = false;
      MultiplierLayout          layout_;
      std::vector<unsigned int> owned_nodes_, owned_frictional_;
      std::vector<unsigned int> nodes_per_process_, multipliers_per_process_;
    };
  } // namespace contact
} // namespace dualcontact
