#pragma once

#include <deal.II/grid/tria.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * The subdomain of every active cell of @p triangulation (by active
     * cell index), for @p n_parts parts: METIS (through
     * dealii::SparsityTools::partition) on the graph of cells that share a
     * face, then every part split into its pieces connected through whole
     * faces (two active cells of one level), so that each subdomain's
     * stiffness matrix has exactly the rigid-body motions as kernel (a
     * part joined by an edge or a vertex only would have a hinge; so would
     * a refined cell joined to a coarser one, which share one vertex: the
     * other vertices of the fine face hang).  The subdomains are numbered by
     * their first cell.  The triangulation's subdomain ids are not touched.
     *
     * Throws, naming `Subdomains per body' / `Cells per subdomain' of
     * `subsection Decomposition' and @p body_name, when @p n_parts exceeds
     * the cells or METIS leaves a part empty.
     */
    template <int dim>
    std::vector<unsigned int>
    partition_cells(const dealii::Triangulation<dim> &triangulation,
                    const unsigned int                n_parts,
                    const std::string                &body_name);
  } // namespace decomposition
} // namespace dualcontact
