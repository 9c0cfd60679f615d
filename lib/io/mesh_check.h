#pragma once

#include <deal.II/grid/tria.h>

#include <string>

namespace dualcontact
{
  namespace io
  {
    /**
     * Throw an ExcMessage naming @p mesh_name and the cell types found if
     * @p triangulation has cells other than quadrilaterals (dim = 2) or
     * hexahedra (dim = 3): deal.II reads triangles, tetrahedra, ... from
     * Gmsh files, but the bodies' finite elements are FE_Q on hypercubes.
     */
    template <int dim>
    void
    check_cell_types(const dealii::Triangulation<dim> &triangulation,
                     const std::string                &mesh_name);

    /**
     * Throw an ExcMessage naming @p mesh_name if a cell of @p triangulation
     * is not a quadrilateral / hexahedron (check_cell_types()), or if an
     * active cell (with the (bi/tri)linear geometry of its vertices) is
     * inverted or degenerate: if the Jacobian determinant at a vertex or at
     * a 2^dim-point Gauss point is not positive, relative to the cell's
     * diameter^dim (tolerance 1e-10).
     */
    template <int dim>
    void
    check_cells(const dealii::Triangulation<dim> &triangulation,
                const std::string                &mesh_name);
  } // namespace io
} // namespace dualcontact
