#pragma once

#include <deal.II/base/mpi.h>

#include <contact/multiplier_layout.h>
#include <decomposition/constraint_rows.h>
#include <decomposition/multiplier_exchange.h>

#include <memory>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * Which process owns which row of TFETI's B when the multipliers are
     * distributed, and the neighbour exchange that F lambda needs with
     * these owners.
     *
     * A row belongs to the process of one subdomain whose B_s touches it:
     * the lowest such subdomain on even rows, the highest on odd ones (a
     * chain of gluing rows alternates between its subdomains, so each gets
     * about half of its interface rows; the lowest alone would give the
     * first subdomain all of them and the last none).  The rows of a
     * contact node stay together (its friction set is one block of the QP):
     * the lowest subdomain over all of them.  A row no subdomain touches (a
     * contact node whose dofs are all prescribed) goes to process 0.
     */
    template <int dim>
    class MultiplierOwnership
    {
    public:
      /**
       * @p rows: B (each process keeps the entries of its own subdomains
       * @p owned_subdomains); @p subdomain_owner: the process of every
       * subdomain; @p node_rows: the rows of each contact node (normal
       * first, then tangential ones).  Collective over @p communicator.
       */
      MultiplierOwnership(
        const ConstraintRows<dim>                    &rows,
        const std::vector<unsigned int>              &subdomain_owner,
        const std::vector<unsigned int>              &owned_subdomains,
        const std::vector<std::vector<unsigned int>> &node_rows,
        const MPI_Comm                                communicator);

      /** This process' rows and the moves to and from the whole vector. */
      const contact::MultiplierLayout &
      layout() const;
      /** The neighbour communication of F lambda. */
      const MultiplierExchange &
      exchange() const;
      /**
       * Per owned subdomain s, for each entry of B_s in order, the position
       * of its row among the exchange's relevant rows (empty for the
       * subdomains of other processes).
       */
      const std::vector<std::vector<unsigned int>> &
      relevant_index() const;
      /** Contact nodes owned per process. */
      const std::vector<unsigned int> &
      nodes_per_process() const;

    private:
      /** Per row, the subdomain chosen to own it (or invalid). */
      static std::vector<unsigned int>
      choose_subdomains(const ConstraintRows<dim>       &rows,
                        const std::vector<unsigned int> &owned_subdomains,
                        const std::vector<std::vector<unsigned int>> &node_rows,
                        const MPI_Comm communicator);
      /** The exchange over every row the owned B_s touch, and the positions
       *  of their entries among those rows. */
      void
      set_up_exchange(const ConstraintRows<dim>       &rows,
                      const std::vector<unsigned int> &owned_subdomains,
                      const std::vector<unsigned int> &row_owner,
                      const MPI_Comm                   communicator);

      contact::MultiplierLayout              layout_;
      std::unique_ptr<MultiplierExchange>    exchange_;
      std::vector<std::vector<unsigned int>> relevant_index_;
      std::vector<unsigned int>              nodes_per_process_;
    };
  } // namespace decomposition
} // namespace dualcontact
