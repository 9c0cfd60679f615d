#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>

#include <fem/cell_family.h>

#include <cmath>
#include <map>

namespace dualcontact
{
  namespace fem
  {
    using namespace dealii;

    namespace
    {
      /** "triangle", "hexahedron", ...: a reference cell in words. */
      std::string
      cell_type_name(const ReferenceCell &type)
      {
        if (type == ReferenceCells::Triangle)
          return "triangle";
        if (type == ReferenceCells::Quadrilateral)
          return "quadrilateral";
        if (type == ReferenceCells::Tetrahedron)
          return "tetrahedron";
        if (type == ReferenceCells::Pyramid)
          return "pyramid";
        if (type == ReferenceCells::Wedge)
          return "wedge (prism)";
        if (type == ReferenceCells::Hexahedron)
          return "hexahedron";
        return type.to_string();
      }


      template <int dim>
      ReferenceCell
      only_cell_type(const Triangulation<dim> &triangulation,
                     const std::string        &mesh_name)
      {
        std::map<ReferenceCell, unsigned int> counts;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (!cell->is_artificial())
            ++counts[cell->reference_cell()];

        // whether there are hypercubes, simplices, other cells: the same
        // on every process of a distributed mesh
        const ReferenceCell hypercube = ReferenceCells::get_hypercube<dim>();
        const ReferenceCell simplex   = ReferenceCells::get_simplex<dim>();
        unsigned int        present[3] = {0, 0, 0};
        for (const auto &[type, count] : counts)
          present[type == hypercube ? 0 : type == simplex ? 1 : 2] = 1;
        if (const auto *parallel = dynamic_cast<
              const parallel::TriangulationBase<dim> *>(&triangulation))
          Utilities::MPI::max(present, parallel->get_communicator(), present);
        if (present[1] == 0 && present[2] == 0)
          return hypercube;
        if (present[0] == 0 && present[2] == 0)
          return simplex;

        std::string listed;
        for (const auto &[type, count] : counts)
          listed += (listed.empty() ? "" : ", ") + std::to_string(count) + " " +
                    cell_type_name(type) + " cell(s)";
        AssertThrow(false,
                    ExcMessage(
                      "The mesh of " + mesh_name + " has " + listed +
                      ": dualcontact needs one kind of cells per body, " +
                      cell_type_name(hypercube) + "s or " +
                      cell_type_name(simplex) +
                      "s (in Gmsh: mesh the body with one element type; "
                      "`Recombine Surface' or `Mesh.RecombineAll = 1' and "
                      "in 3D `Mesh.SubdivisionAlgorithm = 2' give " +
                      cell_type_name(hypercube) + "s only, no "
                      "recombination " +
                      cell_type_name(simplex) + "s only)."));
        return hypercube;
      }
    } // namespace


    template <int dim>
    CellFamily<dim>::CellFamily(const ReferenceCell &cell_type)
        : cell_type_(cell_type)
    {
      AssertThrow(cell_type == ReferenceCells::get_hypercube<dim>() ||
                    cell_type == ReferenceCells::get_simplex<dim>(),
                  ExcMessage("dualcontact has no elements on " +
                             cell_type_name(cell_type) + " cells."));
    }


    template <int dim>
    CellFamily<dim>::CellFamily(const Triangulation<dim> &triangulation,
                                const std::string        &mesh_name)
        : CellFamily(only_cell_type(triangulation, mesh_name))
    {}


    template <int dim>
    bool
    CellFamily<dim>::is_simplex() const
    {
      return cell_type_ == ReferenceCells::get_simplex<dim>();
    }


    template <int dim>
    const ReferenceCell &
    CellFamily<dim>::cell_type() const
    {
      return cell_type_;
    }


    template <int dim>
    ReferenceCell
    CellFamily<dim>::face_type() const
    {
      return cell_type_.face_reference_cell(0);
    }


    template <int dim>
    std::string
    CellFamily<dim>::cells_in_words() const
    {
      const std::string name = cell_type_name(cell_type_);
      return name == "hexahedron"  ? "hexahedra" :
             name == "tetrahedron" ? "tetrahedra" :
                                     name + "s";
    }


    template <int dim>
    std::unique_ptr<FiniteElement<dim>>
    CellFamily<dim>::scalar_element(const unsigned int degree) const
    {
      if (is_simplex())
        return std::make_unique<FE_SimplexP<dim>>(degree);
      return std::make_unique<FE_Q<dim>>(degree);
    }


    template <int dim>
    std::unique_ptr<Mapping<dim>>
    CellFamily<dim>::mapping(const unsigned int degree) const
    {
      if (is_simplex())
        return std::make_unique<MappingFE<dim>>(FE_SimplexP<dim>(1));
      return std::make_unique<MappingQ<dim>>(degree);
    }


    template <int dim>
    unsigned int
    CellFamily<dim>::mapping_degree(const unsigned int degree) const
    {
      return is_simplex() ? 1 : degree;
    }


    template <int dim>
    Quadrature<dim>
    CellFamily<dim>::cell_quadrature(const unsigned int n_points_1d) const
    {
      return cell_type_.get_gauss_type_quadrature<dim>(n_points_1d);
    }


    template <int dim>
    Quadrature<dim - 1>
    CellFamily<dim>::face_quadrature(const unsigned int n_points_1d) const
    {
      return face_type().template get_gauss_type_quadrature<dim - 1>(
        n_points_1d);
    }


    template <int dim>
    Point<dim>
    CellFamily<dim>::unit_point(
      const Mapping<dim>                                &mapping,
      const typename Triangulation<dim>::cell_iterator &cell,
      const Point<dim>                                  &x) const
    {
      if (!is_simplex())
        return mapping.transform_real_to_unit_cell(cell, x);
      // x = v_0 + J xi with the columns of J the edges v_k - v_0 (the
      // reference simplex has its vertex k > 0 at e_k)
      Tensor<2, dim> jacobian;
      for (unsigned int k = 0; k < dim; ++k)
        for (unsigned int d = 0; d < dim; ++d)
          jacobian[d][k] = cell->vertex(k + 1)[d] - cell->vertex(0)[d];
      return Point<dim>(invert(jacobian) * (x - cell->vertex(0)));
    }


    template <int dim>
    Quadrature<dim - 1>
    CellFamily<dim>::face_midpoint_rule(const unsigned int n) const
    {
      if (dim == 2 || !is_simplex())
        return QIterated<dim - 1>(QMidpoint<1>(), n);
      // the reference triangle split into n^2 triangles: per strip j, the
      // n - j triangles pointing up and the n - j - 1 pointing down; their
      // centroids, each of area 1 / (2 n^2)
      std::vector<Point<dim - 1>> points;
      const double                h = 1. / n;
      for (unsigned int j = 0; j < n; ++j)
        for (unsigned int i = 0; i + j < n; ++i)
        {
          Point<dim - 1> up;
          up[0] = (i + 1. / 3) * h;
          up[dim - 2] = (j + 1. / 3) * h;
          points.push_back(up);
          if (i + j + 1 < n)
          {
            Point<dim - 1> down;
            down[0] = (i + 2. / 3) * h;
            down[dim - 2] = (j + 2. / 3) * h;
            points.push_back(down);
          }
        }
      return Quadrature<dim - 1>(points,
                                 std::vector<double>(points.size(),
                                                     0.5 / (n * n)));
    }


    template <int dim>
    bool
    CellFamily<dim>::is_face_dof(const FiniteElement<dim> &fe,
                                 const unsigned int        i,
                                 const unsigned int        face_no)
    {
      const ReferenceCell reference = fe.reference_cell();
      if (reference.is_hyper_cube())
        return fe.has_support_on_face(i, face_no);
      Assert(fe.has_support_points(),
             ExcMessage("is_face_dof needs a nodal element"));
      // the face's plane through its first vertex, with its normal
      const Point<dim> on_face =
        reference.template vertex<dim>(reference.face_to_cell_vertices(
          face_no, 0, /* standard orientation */ 1));
      const Tensor<1, dim> normal =
        reference.template unit_normal_vectors<dim>(face_no);
      return std::abs((fe.unit_support_point(i) - on_face) * normal) < 1e-12;
    }


    template <int dim>
    double
    CellFamily<dim>::lumping_function(const FEFaceValues<dim> &values,
                                      const unsigned int       k,
                                      const unsigned int       q)
    {
      const FiniteElement<dim> &fe = values.get_fe();
      if (dim == 3 && fe.degree == 2 && fe.reference_cell().is_simplex())
      {
        // FE_SimplexP numbers its vertex dofs first, one per vertex
        const bool at_vertex = fe.system_to_component_index(k).second <
                               fe.reference_cell().n_vertices();
        return at_vertex ? 1. / 12 : 1. / 4;
      }
      return values.shape_value(k, q);
    }


    template <int dim>
    unsigned int
    CellFamily<dim>::output_subdivisions(const unsigned int degree) const
    {
      return is_simplex() ? 1 : degree;
    }


    template class CellFamily<2>;
    template class CellFamily<3>;
  } // namespace fem
} // namespace dualcontact
