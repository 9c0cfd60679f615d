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
  } // namespace util
} // namespace dualcontact
