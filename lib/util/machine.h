#pragma once

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
  } // namespace util
} // namespace dualcontact
