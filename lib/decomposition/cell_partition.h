#pragma once

#include <deal.II/grid/tria.h>

#include <decomposition/decomposition_parameters.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * The subdomain of every active cell of @p triangulation (by active
     * cell index), for @p n_parts parts cut by @p partitioner: METIS (through
     * dealii::SparsityTools::partition) on the graph of cells that share a
     * face, or recursive coordinate bisection of the cell centres
     * (bisect_cells()); then every part split into its pieces connected through
     * whole faces (two active cells of one level), so that each subdomain's
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
    partition_cells(const dealii::Triangulation<dim>          &triangulation,
                    const unsigned int                         n_parts,
                    const DecompositionParameters::Partitioner partitioner,
                    const std::string                         &body_name);

    /**
     * The part (0 .. @p n_parts - 1) of every active cell of
     * @p triangulation by recursive coordinate bisection: the cells are cut
     * across the longest extent of their centres' bounding box into two
     * sets of n_1 = floor(@p n_parts / 2) and n_2 parts, at the position
     * that gives the first set the fraction n_1 / @p n_parts of the cells
     * (ties ordered by the other coordinates, so that a cut through a layer
     * of equal centres is the same on every process), and each set is cut
     * again.  On a box of k_1 x k_2 x k_3 cells and a power of two of parts
     * the parts are boxes; the cut follows the cells' centres, not the
     * faces, so on a curved mesh the parts may come in pieces (which
     * partition_cells() separates).
     */
    template <int dim>
    std::vector<unsigned int>
    bisect_cells(const dealii::Triangulation<dim> &triangulation,
                 const unsigned int                n_parts);
  } // namespace decomposition
} // namespace dualcontact
