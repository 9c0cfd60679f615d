#include <deal.II/base/exceptions.h>

#include <contact/multiplier_layout.h>

#include <algorithm>
#include <numeric>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    MultiplierLayout::MultiplierLayout(const unsigned int n_rows)
        : n_rows_(n_rows)
        , communicator_(MPI_COMM_SELF)
        , owned_(complete_index_set(n_rows))
        , owned_rows_(n_rows)
    {
      std::iota(owned_rows_.begin(), owned_rows_.end(), 0u);
    }


    MultiplierLayout::MultiplierLayout(const unsigned int        n_rows,
                                       std::vector<unsigned int> owned_rows,
                                       const MPI_Comm            communicator)
        : n_rows_(n_rows)
        , communicator_(communicator)
        , owned_(n_rows)
        , owned_rows_(std::move(owned_rows))
    {
      Assert(std::is_sorted(owned_rows_.begin(), owned_rows_.end()),
             ExcInternalError());
      owned_.add_indices(owned_rows_.begin(), owned_rows_.end());
      owned_.compress();
    }


    unsigned int
    MultiplierLayout::size() const
    {
      return n_rows_;
    }


    MPI_Comm
    MultiplierLayout::communicator() const
    {
      return communicator_;
    }


    const IndexSet &
    MultiplierLayout::locally_owned() const
    {
      return owned_;
    }


    const std::vector<unsigned int> &
    MultiplierLayout::owned_rows() const
    {
      return owned_rows_;
    }


    void
    MultiplierLayout::initialize(DistributedVector &lambda) const
    {
      lambda.reinit(owned_, communicator_);
    }


    void
    MultiplierLayout::gather(const DistributedVector &lambda,
                             Vector<double>          &whole) const
    {
      AssertDimension(lambda.locally_owned_size(), owned_rows_.size());
      whole.reinit(n_rows_);
      for (unsigned int k = 0; k < owned_rows_.size(); ++k)
        whole(owned_rows_[k]) = lambda.begin()[k];
      // each row is owned by one process: the sum is the row itself
      if (Utilities::MPI::n_mpi_processes(communicator_) > 1)
      {
        const int ierr = MPI_Allreduce(MPI_IN_PLACE,
                                       whole.begin(),
                                       whole.size(),
                                       MPI_DOUBLE,
                                       MPI_SUM,
                                       communicator_);
        AssertThrowMPI(ierr);
      }
    }


    void
    MultiplierLayout::extract(const Vector<double> &whole,
                              DistributedVector    &dst) const
    {
      AssertDimension(whole.size(), n_rows_);
      if (dst.size() != n_rows_)
        initialize(dst);
      for (unsigned int k = 0; k < owned_rows_.size(); ++k)
        dst.begin()[k] = whole(owned_rows_[k]);
    }
  } // namespace contact
} // namespace dualcontact
