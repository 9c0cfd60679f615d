// io::write_contact_surface: contact_N.vtu read back with VTK's XML reader
// (what ParaView uses) has one point per contact node with the documented
// fields, components and values: pressure_Pa, tangential_traction_Pa (3,
// padded in 2D), slip_m (3), gap_m, weight, status (the contact_status
// codes 0 separated, 1 stick, 2 slip, 3 frictionless contact, each one
// distinct) and normal (3).  Four nodes, one of each status, in 2D and 3D.

#include <io/contact_surface_writer.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#ifdef DUALCONTACT_WITH_VTK
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#endif

namespace
{
  int n_failures = 0;

  void
  check(const bool condition, const std::string &what)
  {
    std::cout << (condition ? "ok    " : "FAIL  ") << what << std::endl;
    if (!condition)
      ++n_failures;
  }

#ifdef DUALCONTACT_WITH_VTK
  template <int dim>
  void
  test()
  {
    using namespace dualcontact;
    const std::string      where    = " (" + std::to_string(dim) + "D)";
    const std::vector<int> statuses = {
      io::contact_status::separated,
      io::contact_status::stick,
      io::contact_status::slip,
      io::contact_status::frictionless_contact};
    check(std::set<int>(statuses.begin(), statuses.end()).size() == 4 &&
            statuses == std::vector<int>{0, 1, 2, 3},
          "the status codes are 0, 1, 2, 3 and distinct" + where);

    std::vector<io::ContactSurfaceNode<dim>> nodes(statuses.size());
    for (unsigned int i = 0; i < nodes.size(); ++i)
    {
      auto &node = nodes[i];
      for (unsigned int d = 0; d < dim; ++d)
      {
        node.position[d]            = 0.5 * i + d;
        node.tangential_traction[d] = 10. * i + d + 1;
        node.slip[d]                = 1e-3 * (i + d + 1);
      }
      node.normal[dim - 1] = -1;
      node.pressure        = i == 0 ? 0. : 100. * i;
      node.weight          = 0.25 * (i + 1);
      node.gap             = i == 0 ? 1e-2 : 0.;
      node.status          = statuses[i];
    }
    const std::string name = "contact_surface_" + std::to_string(dim) + ".vtu";
    {
      std::ofstream out(name);
      io::write_contact_surface<dim>(out, nodes);
    }

    auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    reader->SetFileName(name.c_str());
    reader->Update();
    vtkUnstructuredGrid *grid = reader->GetOutput();
    check(grid != nullptr && grid->GetNumberOfPoints() == 4 &&
            grid->GetNumberOfCells() == 4,
          "reads back with 4 points and 4 vertex cells" + where);
    if (grid == nullptr || grid->GetNumberOfPoints() != 4)
      return;
    vtkPointData *data = grid->GetPointData();

    const auto field =
      [&](const std::string &field_name, const int n_components)
    {
      vtkDataArray *array = data->GetArray(field_name.c_str());
      check(array != nullptr &&
              array->GetNumberOfComponents() == n_components &&
              array->GetNumberOfTuples() == 4,
            field_name + " with " + std::to_string(n_components) +
              " component(s)" + where);
      return array != nullptr &&
                 array->GetNumberOfComponents() == n_components ?
               array :
               nullptr;
    };
    double worst = 0;
    if (vtkDataArray *a = field("pressure_Pa", 1))
      for (unsigned int i = 0; i < 4; ++i)
        worst =
          std::max(worst, std::abs(a->GetComponent(i, 0) - nodes[i].pressure));
    if (vtkDataArray *a = field("weight", 1))
      for (unsigned int i = 0; i < 4; ++i)
        worst =
          std::max(worst, std::abs(a->GetComponent(i, 0) - nodes[i].weight));
    if (vtkDataArray *a = field("gap_m", 1))
      for (unsigned int i = 0; i < 4; ++i)
        worst = std::max(worst, std::abs(a->GetComponent(i, 0) - nodes[i].gap));
    if (vtkDataArray *a = field("status", 1))
      for (unsigned int i = 0; i < 4; ++i)
        worst = std::max(worst, std::abs(a->GetComponent(i, 0) - statuses[i]));
    const auto vector_field =
      [&](const std::string &field_name, const auto &value)
    {
      if (vtkDataArray *a = field(field_name, 3))
        for (unsigned int i = 0; i < 4; ++i)
          for (unsigned int d = 0; d < 3; ++d)
            worst = std::max(worst,
                             std::abs(a->GetComponent(i, d) -
                                      (d < dim ? value(nodes[i])[d] : 0.)));
    };
    vector_field("tangential_traction_Pa",
                 [](const auto &node) { return node.tangential_traction; });
    vector_field("slip_m", [](const auto &node) { return node.slip; });
    vector_field("normal", [](const auto &node) { return node.normal; });
    for (unsigned int i = 0; i < 4; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        worst = std::max(worst,
                         std::abs(grid->GetPoint(i)[d] -
                                  (d < dim ? nodes[i].position[d] : 0.)));
    check(worst < 1e-10,
          "positions and field values as written (largest difference " +
            std::to_string(worst) + ")" + where);
  }
#endif
} // namespace


int
main()
{
#ifndef DUALCONTACT_WITH_VTK
  std::cout << "VTK not found at configure time: nothing to read back with"
            << std::endl;
  return 0;
#else
  test<2>();
  test<3>();
  std::cout << (n_failures == 0 ? "all passed" : "FAILED") << std::endl;
  return n_failures == 0 ? 0 : 1;
#endif
}
