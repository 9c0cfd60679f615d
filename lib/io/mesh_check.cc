#include <deal.II/base/exceptions.h>
#include <deal.II/base/geometry_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>

#include <io/mesh_check.h>

#include <deal.II/grid/reference_cell.h>

#include <cmath>
#include <map>
#include <sstream>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    namespace
    {
      /** "triangle", "tetrahedron", ...: a reference cell in words. */
      std::string
      cell_type_name(const dealii::ReferenceCell &type)
      {
        switch (type.n_vertices() + 10 * type.get_dimension())
        {
          case 23:
            return "triangle";
          case 24:
            return "quadrilateral";
          case 34:
            return "tetrahedron";
          case 35:
            return "pyramid";
          case 36:
            return "wedge (prism)";
          case 38:
            return "hexahedron";
          default:
            return type.to_string();
        }
      }
    } // namespace


    template <int dim>
    void
    check_cell_types(const dealii::Triangulation<dim> &triangulation,
                     const std::string                &mesh_name)
    {
      const auto hypercube = dealii::ReferenceCells::get_hypercube<dim>();
      std::map<std::string, unsigned int> others;
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->reference_cell() != hypercube)
          ++others[cell_type_name(cell->reference_cell())];
      if (others.empty())
        return;
      std::string counts;
      for (const auto &[type, count] : others)
        counts += (counts.empty() ? "" : ", ") + std::to_string(count) + " " +
                  type + " cell(s)";
      AssertThrow(false,
                  dealii::ExcMessage(
                    "The mesh of " + mesh_name + " has " + counts +
                    ": dualcontact needs " + cell_type_name(hypercube) +
                    " cells only (in Gmsh: `Recombine Surface' or "
                    "`Mesh.RecombineAll = 1', and in 3D "
                    "`Mesh.SubdivisionAlgorithm = 2' for hexahedra)."));
    }


    template <int dim>
    void
    check_cells(const dealii::Triangulation<dim> &triangulation,
                const std::string                &mesh_name)
    {
      check_cell_types(triangulation, mesh_name);
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
    check_cell_types<2>(const dealii::Triangulation<2> &, const std::string &);
    template void
    check_cell_types<3>(const dealii::Triangulation<3> &, const std::string &);
    template void
    check_cells<2>(const dealii::Triangulation<2> &, const std::string &);
    template void
    check_cells<3>(const dealii::Triangulation<3> &, const std::string &);
  } // namespace io
} // namespace dualcontact
