#include <deal.II/base/exceptions.h>
#include <deal.II/base/geometry_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>

#include <io/mesh_check.h>

#include <cmath>
#include <sstream>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    template <int dim>
    void
    check_cells(const dealii::Triangulation<dim> &triangulation,
                const std::string                &mesh_name)
    {
      using Info = dealii::GeometryInfo<dim>;
      // reference points: the vertices and the 2^dim Gauss points
      std::vector<dealii::Point<dim>> points;
      for (unsigned int v = 0; v < Info::vertices_per_cell; ++v)
        points.push_back(Info::unit_cell_vertex(v));
      const dealii::QGauss<dim> gauss(2);
      for (const auto &point : gauss.get_points())
        points.push_back(point);

      for (const auto &cell : triangulation.active_cell_iterators())
      {
        const double scale = std::pow(cell->diameter(), dim);
        for (const auto &point : points)
        {
          dealii::Tensor<2, dim> jacobian;
          for (unsigned int v = 0; v < Info::vertices_per_cell; ++v)
            jacobian += dealii::outer_product(
              cell->vertex(v),
              Info::d_linear_shape_function_gradient(point, v));
          const double det = dealii::determinant(jacobian);
          if (!(det > 1e-10 * scale))
          {
            std::ostringstream message;
            message << "The mesh of " << mesh_name
                    << " has an inverted or degenerate cell (cell "
                    << cell->id() << ", vertices";
            for (unsigned int v = 0; v < Info::vertices_per_cell; ++v)
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
