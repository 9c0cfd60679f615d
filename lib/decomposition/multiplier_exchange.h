#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_vector.h>

#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * The neighbour communication of TFETI's distributed multipliers.  A
     * process owns some rows of B (its multipliers: the entries of a
     * distributed vector) and needs the values of more of them, the
     * "relevant" rows: every row its subdomains' B_s touch.  F lambda =
     * sum_s B_s K_s^# B_s' lambda then reads lambda on the relevant rows
     * (import()) and adds each subdomain's B_s u_s into the owners' rows
     * (export_add()): point-to-point messages with the processes whose
     * subdomains share rows with this one's, of the shared rows only, in
     * place of an MPI_Allreduce of every multiplier.  The lists of what goes
     * where are set up once (Utilities::MPI::some_to_some).
     */
    class MultiplierExchange
    {
    public:
      using DistributedVector = dealii::TrilinosWrappers::MPI::Vector;

      /**
       * @p owned: this process' rows (of @p n_rows); @p relevant: the rows
       * whose values this process reads or adds to, sorted, a superset of
       * the owned ones; @p relevant_owner: the owning process of each of
       * them.  Collective over @p communicator.
       */
      MultiplierExchange(const dealii::IndexSet          &owned,
                         const std::vector<unsigned int> &relevant,
                         const std::vector<unsigned int> &relevant_owner,
                         const MPI_Comm                   communicator);

      /** Position of relevant row @p row among the (sorted) relevant
       *  rows: the index into import()'s and export_add()'s values. */
      unsigned int
      relevant_index(const unsigned int row) const;

      /**
       * @p values[i] := @p src on relevant row i (sized here): the owned
       * values copied, the others received from their owners.
       */
      void
      import(const DistributedVector &src, std::vector<double> &values) const;
      /**
       * @p dst := on every owned row, the sum of @p values (one per
       * relevant row, the contributions of this process) and of what the
       * other processes add to it.  @p dst must have the owned layout.
       */
      void
      export_add(const std::vector<double> &values,
                 DistributedVector         &dst) const;

    private:
      /** One neighbour: the relevant rows it owns that this process reads
       *  (positions among the relevant rows), and the rows this process owns
       *  that it reads (positions in the owned vector). */
      struct Neighbour
      {
        unsigned int              rank;
        std::vector<unsigned int> ghosts;
        std::vector<unsigned int> owned;
      };

      /** Sends @p sent[n] to neighbour n and receives @p received[n]
       *  (sized by the caller) from it, with message tag @p tag. */
      void
      swap_with_neighbours(const std::vector<std::vector<double>> &sent,
                           std::vector<std::vector<double>>       &received,
                           const int                               tag) const;

      MPI_Comm                  communicator_;
      dealii::IndexSet          owned_;
      std::vector<unsigned int> relevant_;
      /** Per relevant row, its position in the owned vector, or -1. */
      std::vector<int>       owned_position_;
      std::vector<Neighbour> neighbours_;
    };
  } // namespace decomposition
} // namespace dualcontact
