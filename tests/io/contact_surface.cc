// io::write_contact_surface: a contact-surface file, read back with VTK's XML
// readers, has the surface's cells (lines in 2D, quadrilaterals in 3D) and
// the documented point fields with their components and values:
// pressure_Pa, normal_force_N (= pressure * weight), area_weight_m2, gap_m,
// tangential_traction_Pa (3, padded in 2D), slip_m (3), status (the
// contact_status codes 0 separated, 1 stick, 2 slip, 3 frictionless contact,
// -1 no contact node, each distinct) and normal (3).  A surface of two cells
// over four contact nodes (one of each status), a hanging point (the mean of
// two nodes: interpolated values, weight and force 0, status -1) and a point
// beyond the search distance (pressure 0, gap NaN, status -1).  The cells
// owned by process 1 only make a piece of one cell; the .pvtu record of the
// two pieces reads back as the whole surface.

#include <io/contact_surface_writer.h>

#include <vtkCellTypes.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <test_tools.h>
#include <vector>

using test_tools::check;

namespace
{
  template <typename Reader>
  vtkSmartPointer<vtkUnstructuredGrid>
  read(const std::string &name)
  {
    auto reader = vtkSmartPointer<Reader>::New();
    reader->SetFileName(name.c_str());
    reader->Update();
    vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
    return grid;
  }


  template <int dim>
  void
  test()
  {
    using namespace dualcontact;
    const std::string      where    = " (" + std::to_string(dim) + "D)";
    const std::vector<int> statuses = {io::contact_status::separated,
                                       io::contact_status::stick,
                                       io::contact_status::slip,
                                       io::contact_status::frictionless_contact,
                                       io::contact_status::no_contact_node};
    check(std::set<int>(statuses.begin(), statuses.end()).size() == 5 &&
            statuses == std::vector<int>{0, 1, 2, 3, -1},
          "the status codes are 0, 1, 2, 3, -1 and distinct" + where);

    // four contact nodes
    std::vector<io::ContactSurfaceNode<dim>> nodes(4);
    for (unsigned int i = 0; i < nodes.size(); ++i)
    {
      auto &node = nodes[i];
      for (unsigned int d = 0; d < dim; ++d)
      {
        node.tangential_traction[d] = 10. * i + d + 1;
        node.slip[d]                = 1e-3 * (i + d + 1);
      }
      node.normal[dim - 1] = -1;
      node.pressure        = i == 0 ? 0. : 100. * i;
      node.weight          = 0.25 * (i + 1);
      node.gap             = i == 0 ? 1e-2 : 0.;
      node.status          = statuses[i];
    }
    // points: the 4 nodes, a hanging point (mean of nodes 1 and 2), a point
    // beyond the search distance; 2D: two lines, 3D: two quadrilaterals
    std::vector<dealii::Point<dim>> positions(6);
    for (unsigned int p = 0; p < positions.size(); ++p)
      for (unsigned int d = 0; d < dim; ++d)
        positions[p][d] = 0.5 * p + d;
    using Mesh = io::ContactSurfaceMesh<dim>;
    std::vector<typename Mesh::Combination> combinations = {
      {{0, 1.}}, {{1, 1.}}, {{2, 1.}}, {{3, 1.}}, {{1, 0.5}, {2, 0.5}}, {}};
    std::vector<typename Mesh::Cell> cells;
    if constexpr (dim == 2)
      cells = {{{0, 4}}, {{4, 5}}};
    else
      cells = {{{0, 1, 4, 3}}, {{1, 2, 5, 4}}};
    const Mesh mesh(positions, combinations, cells, {0, 1});

    const std::string name  = "contact_surface_" + std::to_string(dim);
    const auto        write = [&](const std::string &file, unsigned int piece)
    {
      std::ofstream out(file);
      io::write_contact_surface<dim>(out, mesh, nodes, piece);
    };
    write(name + ".vtu", dealii::numbers::invalid_unsigned_int);
    write(name + "_rank_0.vtu", 0);
    write(name + "_rank_1.vtu", 1);
    {
      std::ofstream out(name + ".pvtu");
      io::write_contact_surface_record(out,
                                       {name + "_rank_0.vtu",
                                        name + "_rank_1.vtu"});
    }
    {
      std::ifstream     in(name + ".vtu");
      const std::string text((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
      check(text.find("format=\"binary\"") != std::string::npos &&
              text.find("vtkZLibDataCompressor") != std::string::npos &&
              text.find("format=\"ascii\"") == std::string::npos,
            "binary, zlib-compressed data arrays" + where);
    }

    const auto grid      = read<vtkXMLUnstructuredGridReader>(name + ".vtu");
    const int  cell_type = dim == 2 ? VTK_LINE : VTK_QUAD;
    // 2D: the lines use points 0, 4, 5 (not 1, 2, 3); 3D: all six
    const unsigned int n_points = dim == 2 ? 3 : 6;
    check(grid->GetNumberOfCells() == 2 &&
            grid->GetNumberOfPoints() == n_points &&
            grid->GetCellType(0) == cell_type &&
            grid->GetCellType(1) == cell_type,
          "2 " + std::string(dim == 2 ? "line" : "quadrilateral") +
            " cells over " + std::to_string(n_points) + " points" + where);

    // the file's points in order of first use: which mesh point each is
    std::vector<unsigned int> mesh_point;
    for (const auto &c : cells)
      for (const unsigned int p : c)
        if (std::find(mesh_point.begin(), mesh_point.end(), p) ==
            mesh_point.end())
          mesh_point.push_back(p);

    vtkPointData *data  = grid->GetPointData();
    double        worst = 0;
    const auto    compare =
      [&](const std::string &field,
          const unsigned int n_components,
          const auto        &expected) // expected(mesh point, component)
    {
      vtkDataArray *array = data->GetArray(field.c_str());
      const bool    ok =
        array != nullptr &&
        array->GetNumberOfComponents() == static_cast<int>(n_components) &&
        array->GetNumberOfTuples() == n_points;
      check(ok,
            field + " with " + std::to_string(n_components) + " component(s)" +
              where);
      if (!ok)
        return;
      for (unsigned int k = 0; k < n_points; ++k)
        for (unsigned int c = 0; c < n_components; ++c)
        {
          const double value = array->GetComponent(k, c);
          const double want  = expected(mesh_point[k], c);
          if (std::isnan(want))
            worst = std::isnan(value) ? worst : 1e300;
          else
            worst = std::max(worst, std::abs(value - want));
        }
    };
    const auto combined = [&](const unsigned int point, const auto &value)
    {
      double sum = 0;
      for (const auto &[i, coefficient] : combinations[point])
        sum += coefficient * value(nodes[i]);
      return sum;
    };
    const auto own = [&](const unsigned int point, const auto &value)
    { return point < 4 ? value(nodes[point]) : 0.; };
    compare("pressure_Pa",
            1,
            [&](unsigned int p, unsigned int)
            { return combined(p, [](const auto &n) { return n.pressure; }); });
    compare("area_weight_m2",
            1,
            [&](unsigned int p, unsigned int)
            { return own(p, [](const auto &n) { return n.weight; }); });
    compare("normal_force_N",
            1,
            [&](unsigned int p, unsigned int) {
              return own(p,
                         [](const auto &n) { return n.pressure * n.weight; });
            });
    compare("gap_m",
            1,
            [&](unsigned int p, unsigned int)
            {
              return p == 5 ? std::nan("") :
                              combined(p, [](const auto &n) { return n.gap; });
            });
    compare("status",
            1,
            [&](unsigned int p, unsigned int)
            { return p < 4 ? nodes[p].status : -1.; });
    const auto vector = [&](const std::string &field, const auto &member)
    {
      compare(field,
              3,
              [&](unsigned int p, unsigned int c)
              {
                return c < dim ?
                         combined(p,
                                  [&](const auto &n) { return member(n)[c]; }) :
                         0.;
              });
    };
    vector("tangential_traction_Pa",
           [](const auto &n) { return n.tangential_traction; });
    vector("slip_m", [](const auto &n) { return n.slip; });
    vector("normal", [](const auto &n) { return n.normal; });
    for (unsigned int k = 0; k < n_points; ++k)
      for (unsigned int d = 0; d < 3; ++d)
        worst =
          std::max(worst,
                   std::abs(grid->GetPoint(k)[d] -
                            (d < dim ? positions[mesh_point[k]][d] : 0.)));
    check(worst < 1e-12,
          "positions and field values as written (largest difference " +
            std::to_string(worst) + ")" + where);

    const auto piece = read<vtkXMLUnstructuredGridReader>(name + "_rank_1.vtu");
    check(piece->GetNumberOfCells() == 1 &&
            piece->GetNumberOfPoints() == (dim == 2 ? 2 : 4),
          "the piece of process 1: its one cell and the points of it" + where);
    const auto whole = read<vtkXMLPUnstructuredGridReader>(name + ".pvtu");
    check(whole->GetNumberOfCells() == 2 &&
            whole->GetPointData()->GetArray("normal_force_N") != nullptr &&
            whole->GetPointData()->GetArray("status") != nullptr,
          "the .pvtu record reads back as both pieces with the fields" + where);
    for (const std::string suffix :
         {".vtu", "_rank_0.vtu", "_rank_1.vtu", ".pvtu"})
      std::filesystem::remove(name + suffix);
  }
} // namespace


int
main()
{
  test<2>();
  test<3>();
  return test_tools::finish();
}
