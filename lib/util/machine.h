#pragma once

#include <mpi.h>

#include <vector>

namespace dualcontact
{
  namespace util
  {
    /**
     * The processes of MPI_COMM_WORLD that share this machine's memory
     * (MPI_Comm_split_type with MPI_COMM_TYPE_SHARED); 1 in a program
     * without MPI.  Collective over MPI_COMM_WORLD on its first call (the
     * count is kept for the later ones, which are local).  What a replicated
     * object costs the machine: a serial factor under MPI is held by every
     * one of these processes.
     */
    unsigned int
    processes_on_this_machine();

    /**
     * The concatenation, in process order, of @p local of every process of
     * @p communicator, on every process (one MPI_Allgatherv).  Collective.
     */
    std::vector<double>
    concatenate_over_processes(const std::vector<double> &local,
                               const MPI_Comm             communicator);
  } // namespace util
} // namespace dualcontact
