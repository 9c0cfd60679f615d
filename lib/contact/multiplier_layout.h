#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * Which rows of a vector of multipliers this process owns, and the
     * moves between the whole vector (every row, on every process) and a
     * distributed vector of the owned rows: what the undecomposed dual
     * (MultiplierDistribution) and TFETI's (decomposition::
     * MultiplierOwnership) share once each has chosen its owners.  Every
     * row is owned by exactly one process; the owned rows need not be
     * contiguous (a contact node's normal and tangential rows lie apart),
     * so a distributed vector's local entry k is row owned_rows()[k].
     */
    class MultiplierLayout
    {
    public:
      using DistributedVector = dealii::TrilinosWrappers::MPI::Vector;

      /** Every one of @p n_rows rows on this process alone
       *  (MPI_COMM_SELF). */
      explicit MultiplierLayout(const unsigned int n_rows = 0);

      /**
       * Rows @p owned_rows (sorted, each below @p n_rows) on this process of
       * @p communicator; the other processes own the others.
       */
      MultiplierLayout(const unsigned int        n_rows,
                       std::vector<unsigned int> owned_rows,
                       const MPI_Comm            communicator);

      /** The number of rows of the whole vector. */
      unsigned int
      size() const;
      MPI_Comm
      communicator() const;
      /** The owned rows as an index set of all of them. */
      const dealii::IndexSet &
      locally_owned() const;
      /** The owned rows' global indices, in local order. */
      const std::vector<unsigned int> &
      owned_rows() const;

      /** @p lambda := zero with the owned rows (collective). */
      void
      initialize(DistributedVector &lambda) const;
      /** @p whole := every row of @p lambda, on every process
       *  (collective: one MPI_Allreduce of size()). */
      void
      gather(const DistributedVector &lambda,
             dealii::Vector<double>  &whole) const;
      /** @p dst := the owned rows of @p whole (initialized first if its size
       *  is not size(); then collective). */
      void
      extract(const dealii::Vector<double> &whole,
              DistributedVector            &dst) const;

    private:
      unsigned int              n_rows_;
      MPI_Comm                  communicator_;
      dealii::IndexSet          owned_;
      std::vector<unsigned int> owned_rows_;
    };
  } // namespace contact
} // namespace dualcontact
