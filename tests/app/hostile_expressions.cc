// Expression-valued and numeric entries that do not evaluate to finite
// numbers (issue 49), checked where they are used and named:
//  - io::parse_function returns a checked function: a value that is not
//    finite (1/0, sqrt(-1), 1e308*10) at a point throws naming the entry,
//    its subsection and the point; finite points evaluate as before;
//  - a graph obstacle's height that is not finite where the contact search
//    projects, and one whose slope overflows, name `Height function';
//  - a plane obstacle's normal is scaled by its largest component before it
//    is normalized: (1e308, 1e308) and (0, 1e-300) are the directions they
//    point to (their norms overflow / underflow), a zero normal names
//    `Outward normal'.
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/lac/vector.h>

#include <driver/obstacle_parameters.h>
#include <io/function_expression.h>

#include <cmath>
#include <iostream>
#include <string>
#include <test_tools.h>

using namespace dualcontact;
using test_tools::check;
using test_tools::contains;
using test_tools::error_of;

namespace
{
  /** The obstacle of `subsection Obstacle 1' with the entries @p settings. */
  template <int dim>
  std::shared_ptr<const contact::RigidObstacle<dim>>
  make_obstacle(const std::string &settings)
  {
    dealii::ParameterHandler prm;
    prm.enter_subsection("Obstacle 1");
    driver::ObstacleParameters<dim>::declare_parameters(prm);
    prm.leave_subsection();
    prm.parse_input_from_string("subsection Obstacle 1\n" + settings +
                                "\nend\n");
    prm.enter_subsection("Obstacle 1");
    driver::ObstacleParameters<dim> parameters;
    parameters.parse_parameters(prm, "Obstacle 1");
    prm.leave_subsection();
    return parameters.obstacle;
  }

  template <int dim>
  dealii::Tensor<1, dim>
  normal_at(const contact::RigidObstacle<dim> &obstacle,
            const dealii::Point<dim>          &x)
  {
    dealii::Point<dim>     closest;
    dealii::Tensor<1, dim> normal;
    obstacle.project(x, closest, normal);
    return normal;
  }
} // namespace


int
main()
{
  const std::string location = "(`set Traction' in `subsection Body 1/"
                               "Traction 1')";
  // loads: finite where finite, named where not
  {
    const auto function = io::parse_function<2>("1/x; 0", 2, location);
    dealii::Vector<double> values(2);
    function->vector_value(dealii::Point<2>(2, 0), values);
    check(values(0) == 0.5 && values(1) == 0, "1/x at x = 2", values(0));
    const std::string message = error_of(
      [&] { function->vector_value(dealii::Point<2>(0, 0.5), values); });
    check(contains(message,
                   "The expression `1/x; 0' " + location +
                     " is not finite at the point (0, 0.5), where it is "
                     "(inf, 0)"),
          "1/x at x = 0 names the entry and the point");
    for (const std::string expression : {"0; sqrt(-1)", "1e308*10; 0"})
    {
      const auto bad = io::parse_function<2>(expression, 2, location);
      check(contains(error_of([&] { bad->value(dealii::Point<2>(1, 1), 0); }) +
                       error_of([&] { bad->value(dealii::Point<2>(1, 1), 1); }),
                     "The expression `" + expression + "' " + location +
                       " is not finite at the point (1, 1)"),
            "`" + expression + "' named through value()");
    }
  }

  // a graph obstacle: its height where the search projects
  {
    const auto obstacle =
      make_obstacle<2>("set Type = graph\nset Height function = 1/x");
    check(std::abs(normal_at(*obstacle, dealii::Point<2>(2, 1)).norm() - 1) <
            1e-14,
          "1/x is used where it is finite");
    const std::string message =
      error_of([&] { normal_at(*obstacle, dealii::Point<2>(0, 1)); });
    check(contains(message,
                   "The expression `1/x' (`set Height function' in "
                   "`subsection Obstacle 1') is not finite at the point (0)"),
          "1/x at x = 0 names `Height function' and the point");
    const auto steep = make_obstacle<2>(
      "set Type = graph\nset Height function = 1.7e308*tanh(1e9*x)");
    check(contains(error_of([&] { normal_at(*steep, dealii::Point<2>(0, 2)); }),
                   "(`set Height function' in `subsection Obstacle 1') has no "
                   "finite slope where the contact search projects the point "
                   "(0, 2)"),
          "a slope that overflows names `Height function'");
  }

  // plane normals: scaled before they are normalized
  {
    const auto huge = make_obstacle<2>("set Outward normal = 1e308, 1e308");
    const auto n    = normal_at(*huge, dealii::Point<2>(0, 1));
    check(std::abs(n[0] - std::sqrt(0.5)) < 1e-15 &&
            std::abs(n[1] - std::sqrt(0.5)) < 1e-15,
          "(1e308, 1e308) is the diagonal",
          n);
    const auto tiny = make_obstacle<3>("set Outward normal = 0, 1e-300, 0");
    const auto t    = normal_at(*tiny, dealii::Point<3>(0, 1, 0));
    check(t[0] == 0 && t[1] == 1 && t[2] == 0, "(0, 1e-300, 0) is y", t);
    const auto mixed =
      make_obstacle<3>("set Outward normal = 1e308, -1e308, 1e308");
    const auto m = normal_at(*mixed, dealii::Point<3>(0, 0, 1));
    check(std::abs(m[0] - 1 / std::sqrt(3.)) < 1e-15 &&
            std::abs(m[1] + 1 / std::sqrt(3.)) < 1e-15,
          "(1e308, -1e308, 1e308) is the scaled diagonal",
          m);
    check(contains(error_of([&]
                            { make_obstacle<2>("set Outward normal = 0, 0"); }),
                   "(`set Outward normal' in `subsection Obstacle 1')"),
          "a zero normal names `Outward normal'");
  }
  return test_tools::finish();
}
