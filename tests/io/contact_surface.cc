// io::write_contact_surface: contact_N.vtu, read back, has one point and one
// vertex cell per contact node with the documented fields, components and
// values: pressure_Pa, tangential_traction_Pa (3,
// padded in 2D), slip_m (3), gap_m, weight, status (the contact_status
// codes 0 separated, 1 stick, 2 slip, 3 frictionless contact, each one
// distinct) and normal (3).  Four nodes, one of each status, in 2D and 3D.
// The file is parsed here directly (the writer writes ASCII XML by hand),
// so that the test does not depend on VTK being found at configure time.

#include <io/contact_surface_writer.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include <sstream>

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

  /**
   * The numbers of the DataArray named NAME (or, for NAME empty, of the
   * first DataArray after <Points>) and its NumberOfComponents (1 if not
   * given); empty if there is no such array.
   */
  std::pair<std::vector<double>, int>
  read_array(const std::string &text, const std::string &name)
  {
    std::size_t begin = name.empty() ?
                          text.find("<DataArray", text.find("<Points>")) :
                          text.find("Name=\"" + name + "\"");
    if (begin == std::string::npos)
      return {};
    begin                      = text.rfind("<DataArray", begin);
    const std::size_t tag_end  = text.find('>', begin);
    const std::string tag      = text.substr(begin, tag_end - begin);
    int               n_comp   = 1;
    const std::size_t comp_pos = tag.find("NumberOfComponents=\"");
    if (comp_pos != std::string::npos)
      n_comp = std::stoi(tag.substr(comp_pos + 20));
    const std::size_t   end = text.find("</DataArray>", tag_end);
    std::istringstream  numbers(text.substr(tag_end + 1, end - tag_end - 1));
    std::vector<double> values;
    double              v;
    while (numbers >> v)
      values.push_back(v);
    return {values, n_comp};
  }


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

    std::ifstream     in(name);
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    check(text.find("NumberOfPoints=\"4\" NumberOfCells=\"4\"") !=
              std::string::npos &&
            read_array(text, "types").first == std::vector<double>(4, 1.),
          "4 points and 4 vertex cells" + where);

    const auto field =
      [&](const std::string &field_name, const int n_components)
    {
      const auto [values, n] = read_array(text, field_name);
      const bool ok          = n == n_components && values.size() == 4u * n;
      check(ok,
            field_name + " with " + std::to_string(n_components) +
              " component(s)" + where);
      return ok ? values : std::vector<double>();
    };
    double     worst = 0;
    const auto scalar_field =
      [&](const std::string &field_name, const auto &value)
    {
      const std::vector<double> a = field(field_name, 1);
      for (unsigned int i = 0; i < a.size(); ++i)
        worst = std::max(worst, std::abs(a[i] - value(nodes[i])));
    };
    scalar_field("pressure_Pa", [](const auto &node) { return node.pressure; });
    scalar_field("weight", [](const auto &node) { return node.weight; });
    scalar_field("gap_m", [](const auto &node) { return node.gap; });
    scalar_field("status",
                 [](const auto &node) { return double(node.status); });
    const auto vector_field =
      [&](const std::string &field_name, const auto &value)
    {
      const std::vector<double> a = field(field_name, 3);
      for (unsigned int i = 0; i < a.size() / 3; ++i)
        for (unsigned int d = 0; d < 3; ++d)
          worst = std::max(worst,
                           std::abs(a[3 * i + d] -
                                    (d < dim ? value(nodes[i])[d] : 0.)));
    };
    vector_field("tangential_traction_Pa",
                 [](const auto &node) { return node.tangential_traction; });
    vector_field("slip_m", [](const auto &node) { return node.slip; });
    vector_field("normal", [](const auto &node) { return node.normal; });
    const auto [points, n_point_components] = read_array(text, "");
    check(n_point_components == 3 && points.size() == 12,
          "4 points with 3 coordinates" + where);
    for (unsigned int i = 0; i < points.size() / 3; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        worst = std::max(worst,
                         std::abs(points[3 * i + d] -
                                  (d < dim ? nodes[i].position[d] : 0.)));
    check(worst < 1e-10,
          "positions and field values as written (largest difference " +
            std::to_string(worst) + ")" + where);
  }
} // namespace


int
main()
{
  test<2>();
  test<3>();
  std::cout << (n_failures == 0 ? "all passed" : "FAILED") << std::endl;
  return n_failures == 0 ? 0 : 1;
}
