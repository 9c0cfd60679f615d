#pragma once

#include <deal.II/grid/tria.h>

#include <string>

namespace dualcontact
{
  namespace io
  {
    /**
     * Throw an ExcMessage naming @p mesh_name if @p triangulation mixes
     * cell types or has cells dualcontact has no elements for (pyramids,
     * wedges; fem::CellFamily), or if an active cell (with the geometry of
     * its vertices: (bi/tri)linear on hypercubes, affine on simplices) is
     * inverted or degenerate: if the Jacobian determinant at a vertex or
     * at a Gauss point is not positive, relative to the cell's
     * diameter^dim (tolerance 1e-10).
     */
    template <int dim>
    void
    check_cells(const dealii::Triangulation<dim> &triangulation,
                const std::string                &mesh_name);
  } // namespace io
} // namespace dualcontact
