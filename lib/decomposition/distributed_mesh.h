#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include <decomposition/decomposition_parameters.h>

#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * The bodies' meshes for TFETI on distributed processes (`Mesh
     * distribution = distributed' in `subsection Decomposition'): every
     * body is cut into its subdomains on the serial mesh (partition_cells(),
     * the same cut as on a replicated mesh), the subdomains of all bodies go
     * to the processes by the rule of TFETIDual (largest first onto the
     * process with the fewest dofs so far), and each body becomes a
     * dealii::parallel::fullydistributed::Triangulation whose locally owned
     * cells are exactly the cells of this process' subdomains, plus one
     * layer of ghost cells.  No process keeps the whole mesh: the serial
     * meshes live only while this object is built (every process builds
     * them from the serial description, the way the .prm gives them).
     *
     * What it hands on: the triangulations, the subdomain of every locally
     * relevant cell (owned or ghost), and the owner of every subdomain.
     */
    template <int dim>
    class DistributedMesh
    {
    public:
      /**
       * Cuts and distributes @p serial (one serial mesh per body, named
       * @p names; given by value: they are freed here) for finite elements
       * of degree @p fe_degree (the dofs of a subdomain weigh its owner
       * choice).  Collective over @p communicator.  Throws, naming the
       * parameter, when a body has fewer cells than subdomains or a process
       * would own no cell of any body.
       */
      DistributedMesh(
        std::vector<std::shared_ptr<dealii::Triangulation<dim>>> serial,
        const std::vector<std::string>                          &names,
        const unsigned int                                       fe_degree,
        const DecompositionParameters                           &parameters,
        const MPI_Comm                                           communicator);

      /** The distributed mesh of body @p b. */
      std::shared_ptr<dealii::Triangulation<dim>>
      triangulation(const unsigned int b) const;

      /** Subdomains of body @p b (a part in pieces counts its pieces). */
      unsigned int
      n_subdomains(const unsigned int b) const;

      /** The subdomain (0 .. n_subdomains(b) - 1) of the locally relevant
       *  active cell @p active_cell_index of body @p b. */
      unsigned int
      subdomain_of_cell(const unsigned int b,
                        const unsigned int active_cell_index) const;

      /** The process of every subdomain, the bodies' one after the other
       *  (body b's from sum_{c < b} n_subdomains(c) on). */
      const std::vector<unsigned int> &
      owners() const;

      /** Active cells of all bodies owned by each process. */
      const std::vector<unsigned int> &
      cells_per_process() const;

    private:
      std::vector<std::shared_ptr<dealii::Triangulation<dim>>> meshes_;
      std::vector<unsigned int>                                n_subdomains_;
      /** Per body, per active cell of its distributed mesh: the subdomain
       *  (numbers::invalid_unsigned_int for a cell that is neither owned
       *  nor ghost). */
      std::vector<std::vector<unsigned int>> subdomain_of_cell_;
      std::vector<unsigned int>              owners_;
      std::vector<unsigned int>              cells_per_process_;
    };


    /**
     * The process of each of the subdomains of sizes @p sizes (their dofs):
     * longest processing time first, each onto the process with the least
     * load so far; ties keep the lower subdomain number and process.  The
     * one rule of TFETIDual on a replicated mesh and of DistributedMesh.
     */
    std::vector<unsigned int>
    assign_subdomains_to_processes(const std::vector<unsigned long> &sizes,
                                   const unsigned int n_processes);
  } // namespace decomposition
} // namespace dualcontact
