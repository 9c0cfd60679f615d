#include <deal.II/base/exceptions.h>
#include <deal.II/base/geometry_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>

#include <fem/cell_family.h>
#include <io/mesh_check.h>

#include <cmath>
#include <sstream>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    namespace
    {
      /**
       * The Jacobian of the vertex geometry of @p cell at the unit point
       * @p xi: (bi/tri)linear on a hypercube; on a simplex the affine map
       * of its vertices (xi unused).
       */
      template <int dim>
      dealii::Tensor<2, dim>
      vertex_jacobian(
        const typename dealii::Triangulation<dim>::active_cell_iterator &cell,
        const dealii::Point<dim>                                        &xi,
        const bool simplex)
      {
        dealii::Tensor<2, dim> jacobian;
        if (simplex)
        {
          for (unsigned int d = 0; d < dim; ++d)
            for (unsigned int e = 0; e < dim; ++e)
              jacobian[e][d] = cell->vertex(d + 1)[e] - cell->vertex(0)[e];
          return jacobian;
        }
        using Info = dealii::GeometryInfo<dim>;
        for (unsigned int v = 0; v < Info::vertices_per_cell; ++v)
          jacobian += dealii::outer_product(
            cell->vertex(v), Info::d_linear_shape_function_gradient(xi, v));
        return jacobian;
      }
    } // namespace


    template <int dim>
    void
    check_cells(const dealii::Triangulation<dim> &triangulation,
                const std::string                &mesh_name)
    {
      const fem::CellFamily<dim>      family(triangulation, mesh_name);
      const dealii::ReferenceCell     reference = family.cell_type();
      // reference points: the vertices and the Gauss points of degree 3
      std::vector<dealii::Point<dim>> points;
      for (const unsigned int v : reference.vertex_indices())
        points.push_back(reference.template vertex<dim>(v));
      const dealii::Quadrature<dim> gauss = family.cell_quadrature(2);
      for (const auto &point : gauss.get_points())
        points.push_back(point);

      for (const auto &cell : triangulation.active_cell_iterators())
      {
        if (cell->is_artificial())
          continue;
        const double scale = std::pow(cell->diameter(), dim);
        for (const auto &point : points)
        {
          const double det = dealii::determinant(
            vertex_jacobian<dim>(cell, point, family.is_simplex()));
          if (!(det > 1e-10 * scale))
          {
            std::ostringstream message;
            message << "The mesh of " << mesh_name
                    << " has an inverted or degenerate cell (cell "
                    << cell->id() << ", vertices";
            for (const unsigned int v : cell->vertex_indices())
              message << (v == 0 ? " (" : ", (") << cell->vertex(v) << ")";
            message << "): the Jacobian determinant is " << det
                    << " at the reference point (" << point
                    << "); cells must have positive measure with "
                       "vertices in deal.II/Gmsh order.";
            AssertThrow(false, dealii::ExcMessage(message.str()));
          }
        }
      }
    }


    template void
    check_cells<2>(const dealii::Triangulation<2> &, const std::string &);
    template void
    check_cells<3>(const dealii::Triangulation<3> &, const std::string &);
  } // namespace io
} // namespace dualcontact
