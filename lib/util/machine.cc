#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <util/machine.h>

namespace dualcontact
{
  namespace util
  {
    namespace
    {
      unsigned int
      count_processes_on_this_machine()
      {
        if (!dealii::Utilities::MPI::job_supports_mpi())
          return 1;
        MPI_Comm  machine;
        const int rank =
          dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
        int ierr = MPI_Comm_split_type(
          MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &machine);
        AssertThrowMPI(ierr);
        int size = 1;
        ierr     = MPI_Comm_size(machine, &size);
        AssertThrowMPI(ierr);
        ierr = MPI_Comm_free(&machine);
        AssertThrowMPI(ierr);
        return static_cast<unsigned int>(size);
      }
    } // namespace


    unsigned int
    processes_on_this_machine()
    {
      // the machine's processes do not change during a run: counted once
      static const unsigned int count = count_processes_on_this_machine();
      return count;
    }


    std::vector<double>
    concatenate_over_processes(const std::vector<double> &local,
                               const MPI_Comm             communicator)
    {
      const std::vector<unsigned int> sizes =
        dealii::Utilities::MPI::all_gather(
          communicator, static_cast<unsigned int>(local.size()));
      std::vector<int> counts(sizes.begin(), sizes.end()),
        offsets(sizes.size(), 0);
      for (unsigned int p = 1; p < sizes.size(); ++p)
        offsets[p] = offsets[p - 1] + counts[p - 1];
      std::vector<double> all(offsets.back() + counts.back());
      const int           ierr = MPI_Allgatherv(local.data(),
                                      local.size(),
                                      MPI_DOUBLE,
                                      all.data(),
                                      counts.data(),
                                      offsets.data(),
                                      MPI_DOUBLE,
                                      communicator);
      AssertThrowMPI(ierr);
      return all;
    }
  } // namespace util
} // namespace dualcontact
