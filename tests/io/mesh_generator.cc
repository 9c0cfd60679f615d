// io::MeshGenerator + io::Placement: every generator gives the documented
// boundary ids, and after a rotation and a translation the refined curved
// boundaries still lie on the placed circle/sphere/cylinder (the manifolds
// follow the placement).  Prints one line per case; exits 1 on a failure.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

#include <io/mesh_generator.h>
#include <io/placement.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <test_tools.h>

using test_tools::check;

namespace
{
  /**
   * Build the mesh of @p generator, rotated by 40 degrees (about (1, 2, 3)
   * in 3D) and moved to @p center, refined twice; check its boundary ids and
   * that the vertices on boundary id 0 have distance @p radius from the
   * placed centre (3D cylinder: from the placed axis; box: ids only).
   */
  template <int dim>
  void
  check_generator(const std::string                          &generator,
                  const std::set<dealii::types::boundary_id> &expected_ids)
  {
    dealii::ParameterHandler prm;
    dualcontact::io::MeshGenerator<dim>::declare_parameters(prm);
    dualcontact::io::Placement<dim>::declare_parameters(prm);
    const double radius = 0.3;
    prm.enter_subsection("Mesh");
    prm.set("Generator", generator);
    prm.set("Radius", radius);
    prm.set("Half length", 0.7);
    prm.set("Global refinements", "2");
    prm.leave_subsection();
    prm.enter_subsection("Placement");
    prm.set("Rotation angle", 40.);
    prm.set("Rotation axis", "1, 2, 3");
    prm.set("Translation", dim == 2 ? "1, 2" : "1, 2, 3");
    prm.leave_subsection();

    dualcontact::io::MeshGenerator<dim> mesh;
    dualcontact::io::Placement<dim>     placement;
    mesh.parse_parameters(prm, "Body 1", ".");
    placement.parse_parameters(prm, "Body 1");
    dealii::Triangulation<dim> triangulation;
    mesh.create(triangulation, placement, "Body 1");

    const std::vector<dealii::types::boundary_id> ids =
      triangulation.get_boundary_ids();
    check(std::set<dealii::types::boundary_id>(ids.begin(), ids.end()) ==
            expected_ids,
          std::to_string(dim) + "D " + generator + ": boundary ids");

    const dealii::Point<dim> center = placement(dealii::Point<dim>());
    dealii::Tensor<1, dim>   axis;
    axis[0]          = 1;
    axis             = placement.rotate(axis);
    double max_error = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const auto face : cell->face_indices())
        if (cell->face(face)->at_boundary() &&
            cell->face(face)->boundary_id() == 0)
          for (const auto v : cell->face(face)->vertex_indices())
          {
            dealii::Tensor<1, dim> offset =
              cell->face(face)->vertex(v) - center;
            if (generator == "cylinder")
              offset -= (offset * axis) * axis;
            max_error = std::max(max_error, std::abs(offset.norm() - radius));
          }
    if (generator == "box")
      return;
    std::ostringstream error;
    error << std::scientific << std::setprecision(1) << max_error;
    check(max_error < 1e-12,
          std::to_string(dim) + "D " + generator +
            ": refined boundary on the placed surface (error " + error.str() +
            ")");
  }
} // namespace


int
main()
{
  check_generator<2>("ball", {0});
  check_generator<2>("half ball", {0, 1});
  check_generator<3>("ball", {0});
  check_generator<3>("half ball", {0, 1});
  check_generator<2>("quarter ball", {0, 1, 2});
  check_generator<3>("quarter ball", {0, 1, 2, 3});
  check_generator<2>("cylinder", {0, 1, 2});
  check_generator<3>("cylinder", {0, 1, 2});
  check_generator<2>("box", {0, 1, 2, 3});
  check_generator<3>("box", {0, 1, 2, 3, 4, 5});
  return test_tools::finish();
}
