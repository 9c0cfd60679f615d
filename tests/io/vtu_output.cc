// io::write_solution: the files ParaView opens can be read back with VTK's
// own XML readers (solution.pvtu with its body_N.vtu pieces), and carry the
// documented fields with the right number of components and values:
// displacement_m (3, padded in 2D), stress_Pa and strain (9), scalars
// von_mises_stress_Pa, material_id, body_id.  Two 2D plane-strain bodies
// on rollers under a uniform traction (uniform stress sigma_xx = 1 MPa).

#include <deal.II/base/function.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <fem/cholmod_solver.h>
#include <fem/elastic_body.h>
#include <io/output_folder.h>
#include <io/solution_writer.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <test_tools.h>
#include <vector>

#ifdef DUALCONTACT_WITH_VTK
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#endif


using test_tools::check;

int
main()
{
#ifndef DUALCONTACT_WITH_VTK
  std::cout << "VTK not found at configure time: nothing to read back with"
            << std::endl;
  return 0;
#else
  using namespace dualcontact;
  constexpr int dim = 2;

  std::vector<std::unique_ptr<fem::ElasticBody<dim>>> bodies;
  std::vector<dealii::Vector<double>>                 displacements(2);
  for (unsigned int b = 0; b < 2; ++b)
  {
    auto triangulation = std::make_shared<dealii::Triangulation<dim>>();
    dealii::GridGenerator::subdivided_hyper_rectangle(
      *triangulation,
      {2, 1},
      dealii::Point<dim>(b * 3., 0),
      dealii::Point<dim>(b * 3. + 2, 1),
      true);
    for (const auto &cell : triangulation->active_cell_iterators())
      cell->set_material_id(b);
    auto body = std::make_unique<fem::ElasticBody<dim>>(
      "Body " + std::to_string(b + 1),
      triangulation,
      2,
      std::map<dealii::types::material_id, fem::IsotropicMaterial>{
        {b, fem::IsotropicMaterial(1e9, 0.25)}});
    // rollers: u_x = 0 at x = min (id 0), u_y = 0 at y = 0 (id 2)
    body->set_dirichlet_conditions(
      {{0,
        dealii::ComponentMask(std::vector<bool>{true, false}),
        std::make_shared<dealii::Functions::ZeroFunction<dim>>(dim)},
       {2,
        dealii::ComponentMask(std::vector<bool>{false, true}),
        std::make_shared<dealii::Functions::ZeroFunction<dim>>(dim)}});
    body->set_traction_conditions(
      {{1,
        std::make_shared<dealii::Functions::ConstantFunction<dim>>(
          std::vector<double>{1e6, 0.})}});
    body->setup();
    body->assemble();
    fem::CholmodSolver solver;
    body->solve(solver, displacements[b]);
    bodies.push_back(std::move(body));
  }

  const std::string folder_name = "vtu_output_test";
  std::filesystem::remove_all(folder_name);
  {
    io::OutputFolder folder(folder_name, "(test)");
    io::write_solution<dim>(folder, bodies, displacements);
    folder.commit();
  }

  auto reader = vtkSmartPointer<vtkXMLPUnstructuredGridReader>::New();
  reader->SetFileName((folder_name + "/solution.pvtu").c_str());
  reader->Update();
  vtkUnstructuredGrid *grid = reader->GetOutput();
  check(grid != nullptr && grid->GetNumberOfPoints() > 0,
        "solution.pvtu and its pieces read back (" +
          std::to_string(grid->GetNumberOfPoints()) + " points)");

  vtkPointData                                  *data   = grid->GetPointData();
  const std::vector<std::pair<std::string, int>> fields = {
    {"displacement_m", 3},
    {"stress_Pa", 9},
    {"strain", 9},
    {"von_mises_stress_Pa", 1},
    {"material_id", 1},
    {"body_id", 1}};
  for (const auto &[name, n_components] : fields)
  {
    vtkDataArray *array = data->GetArray(name.c_str());
    check(array != nullptr && array->GetNumberOfComponents() == n_components,
          "field " + name + " with " + std::to_string(n_components) +
            " components");
  }

  if (test_tools::failures == 0)
  {
    double range[2];
    data->GetArray("body_id")->GetRange(range);
    check(range[0] == 1 && range[1] == 2, "body ids 1 and 2");
    data->GetArray("material_id")->GetRange(range);
    check(range[0] == 0 && range[1] == 1, "material ids 0 and 1");
    // uniform stress: sigma_xx = 1e6 Pa everywhere (float precision)
    data->GetArray("stress_Pa")->GetRange(range, 0);
    check(std::abs(range[0] - 1e6) < 1 && std::abs(range[1] - 1e6) < 1,
          "stress_Pa xx = 1e6 Pa everywhere");
    data->GetArray("displacement_m")->GetRange(range, -1);
    const double expected = bodies[0]->max_displacement(displacements[0]);
    check(std::abs(range[1] - expected) < 1e-6 * expected,
          "largest |displacement_m| equals the body's max displacement");
  }
  std::filesystem::remove_all(folder_name);
  return test_tools::finish();
#endif
}
