// Contact discretization checks, 2D and 3D, Q1 and Q2:
//  - a box above a rigid plane: every bottom node is a contact node, gap =
//    distance to the plane, normal = -plane normal, weights sum to the
//    bottom area, frames orthonormal;
//  - a curved rigid foundation (graph obstacle): the gap equals a brute-force
//    distance to the graph;
//  - two stacked boxes with non-matching meshes: for the same linear field
//    on both bodies B_N u = 0 and B_T u = 0 (the master interpolation is
//    exact for linear fields); for the upper body moved by -delta along the
//    normal direction, B_N u = delta;
//  - a prescribed (inhomogeneous Dirichlet) displacement on the slave body
//    moves into the offset: B_full u_D = offset;
//  - a pair whose master is out of reach is a clear error.

#include <deal.II/base/function.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/vector_tools.h>

#include <contact/contact_discretization.h>

#include <test_tools.h>

#include "unit_box.h"

#include <iostream>

using namespace dealii;
using namespace dualcontact;

using test_tools::check;

template <int dim>
double
frame_error(const contact::ContactNode<dim> &node)
{
  double error = std::abs(node.normal.norm() - 1);
  for (const auto &t : node.tangents)
    error =
      std::max({error, std::abs(t.norm() - 1), std::abs(t * node.normal)});
  if (dim == 3)
    error =
      std::max(error, std::abs(node.tangents[0] * node.tangents[dim - 2]));
  return error;
}

template <int dim>
void
run(const unsigned int degree)
{
  std::cout << dim << "D Q" << degree << std::endl;
  const types::boundary_id bottom = 2 * (dim - 1), top = 2 * dim - 1;
  {
    auto body = make_unit_box<dim>("box", 0.1, 4, degree);
    body->setup();
    Tensor<1, dim> up;
    up[dim - 1] = 1;
    contact::ContactPair<dim> pair;
    pair.name           = "box-plane";
    pair.slave_boundary = bottom;
    pair.obstacle =
      std::make_shared<contact::PlaneObstacle<dim>>(Point<dim>(), up);
    contact::ContactDiscretization<dim> contact({body.get()}, {pair});
    const unsigned int expected_nodes = Utilities::pow(4 * degree + 1, dim - 1);
    check(contact.n_nodes() == expected_nodes,
          "plane: contact nodes",
          contact.n_nodes());
    double gap_error = 0, normal_error = 0, frames = 0, area = 0;
    for (const auto &node : contact.nodes())
    {
      gap_error    = std::max(gap_error, std::abs(node.gap - 0.1));
      normal_error = std::max(normal_error, (node.normal + up).norm());
      frames       = std::max(frames, frame_error(node));
      area += node.weight;
    }
    check(gap_error < 1e-14, "plane: max |gap - 0.1|", gap_error);
    check(normal_error < 1e-14, "plane: max |n + e_up|", normal_error);
    check(frames < 1e-14, "plane: frames orthonormal", frames);
    check(std::abs(area - 1) < 1e-13, "plane: sum of weights - 1", area - 1);
    check(contact.normal_matrix().m() == expected_nodes &&
            contact.tangential_matrix().m() == (dim - 1) * expected_nodes,
          "plane: B_N, B_T rows",
          contact.tangential_matrix().m());
  }
  {
    // Curved foundation: h = 0.2 sin(x_1) (+ 0.1 x_2^2 in 3D) - 0.3
    auto body = make_unit_box<dim>("box", 0.1, 3, degree);
    body->setup();
    const std::string expression =
      dim == 2 ? "0.2*sin(x) - 0.3" : "0.2*sin(x) + 0.1*y^2 - 0.3";
    auto height = std::make_shared<FunctionParser<dim - 1>>(1);
    height->initialize(dim == 2 ? "x" : "x,y", expression, {});
    contact::ContactPair<dim> pair;
    pair.name           = "box-graph";
    pair.slave_boundary = bottom;
    pair.obstacle =
      std::make_shared<contact::GraphObstacle<dim>>(height, expression);
    contact::ContactDiscretization<dim> contact({body.get()}, {pair});
    double                              error = 0;
    for (const auto &node : contact.nodes())
    {
      // brute force: sample the graph finely around the node
      double    best = 1e300;
      const int m    = dim == 2 ? 20000 : 400;
      for (int i = -m; i <= m; ++i)
        for (int j = (dim == 2 ? 0 : -m); j <= (dim == 2 ? 0 : m); ++j)
        {
          Point<dim - 1> s;
          s[0] = node.position[0] + 1.0 * i / m;
          if (dim == 3)
            s[dim - 2] = node.position[dim - 2] + 1.0 * j / m;
          Point<dim> y;
          for (unsigned int d = 0; d + 1 < dim; ++d)
            y[d] = s[d];
          y[dim - 1] = height->value(s);
          best       = std::min(best, y.distance(node.position));
        }
      error = std::max(error, std::abs(node.gap - best));
    }
    check(error < (dim == 2 ? 1e-8 : 2e-5),
          "graph: max |gap - brute-force distance|",
          error);
  }
  {
    // Upper box (slave, 3 cells per direction) on a lower box (master, 4).
    auto lower = make_unit_box<dim>("lower", 0, 4, degree);
    auto upper = make_unit_box<dim>("upper", 1, 3, degree);
    lower->setup();
    upper->setup();
    contact::ContactPair<dim> pair;
    pair.name            = "upper-lower";
    pair.slave_body      = 1;
    pair.slave_boundary  = bottom;
    pair.master_body     = 0;
    pair.master_boundary = top;
    contact::ContactDiscretization<dim> contact({lower.get(), upper.get()},
                                                {pair});
    double                              gap = 0;
    for (const auto &node : contact.nodes())
      gap = std::max(gap, std::abs(node.gap));
    check(gap < 1e-14, "two bodies: max |gap|", gap);

    FunctionParser<dim> linear(dim);
    linear.initialize(dim == 2 ? "x,y" : "x,y,z",
                      dim == 2 ? "0.01*x - 0.02*y + 0.003; 0.015*x + 0.01*y" :
                                 "0.01*x - 0.02*y + 0.005*z; 0.015*x + 0.01*y "
                                 "- 0.001; 0.002*x - 0.004*y + 0.01*z",
                      {});
    Vector<double> u(contact.n_dofs()), ul(lower->n_dofs()),
      uu(upper->n_dofs());
    VectorTools::interpolate(lower->mapping(),
                             lower->dof_handler(),
                             linear,
                             ul);
    VectorTools::interpolate(upper->mapping(),
                             upper->dof_handler(),
                             linear,
                             uu);
    for (unsigned int i = 0; i < ul.size(); ++i)
      u(i) = ul(i);
    for (unsigned int i = 0; i < uu.size(); ++i)
      u(contact.body_offset(1) + i) = uu(i);
    Vector<double> bn(contact.n_nodes()), bt((dim - 1) * contact.n_nodes());
    contact.normal_matrix().vmult(bn, u);
    contact.tangential_matrix().vmult(bt, u);
    check(bn.linfty_norm() + bt.linfty_norm() < 1e-15,
          "two bodies: |B u| for one linear field",
          bn.linfty_norm() + bt.linfty_norm());

    // upper body moved down by delta: u_s - u_m = -delta e_up, n = -e_up
    const double delta = 1e-3;
    u                  = 0;
    Functions::ConstantFunction<dim> shift(
      [&]
      {
        std::vector<double> v(dim, 0.);
        v[dim - 1] = -delta;
        return v;
      }());
    VectorTools::interpolate(upper->mapping(), upper->dof_handler(), shift, uu);
    for (unsigned int i = 0; i < uu.size(); ++i)
      u(contact.body_offset(1) + i) = uu(i);
    contact.normal_matrix().vmult(bn, u);
    Vector<double> expected(contact.n_nodes());
    expected.add(delta);
    bn -= expected;
    check(bn.linfty_norm() < 1e-15,
          "two bodies: B_N (rigid shift) - delta",
          bn.linfty_norm());
  }
  {
    // Prescribed displacement on the slave's bottom face itself.
    auto                body = make_unit_box<dim>("box", 0.1, 2, degree);
    std::vector<double> value(dim, 0.);
    value[dim - 1] = -0.05;
    value[0]       = 0.02;
    body->set_dirichlet_conditions(
      {{bottom,
        ComponentMask(dim, true),
        std::make_shared<Functions::ConstantFunction<dim>>(value)}});
    body->setup();
    Tensor<1, dim> up;
    up[dim - 1] = 1;
    contact::ContactPair<dim> pair;
    pair.name                       = "prescribed";
    pair.slave_boundary             = bottom;
    pair.first_tangent_direction[0] = 1;
    pair.obstacle =
      std::make_shared<contact::PlaneObstacle<dim>>(Point<dim>(), up);
    contact::ContactDiscretization<dim> contact({body.get()}, {pair});
    double                              offset_error = 0, bound_error = 0;
    for (unsigned int i = 0; i < contact.n_nodes(); ++i)
    {
      offset_error =
        std::max(offset_error, std::abs(contact.normal_offset()(i) - 0.05));
      bound_error =
        std::max(bound_error, std::abs(contact.normal_bound()(i) - 0.05));
      // t1 = e_x: offset_T = 0.02 along it
      offset_error =
        std::max(offset_error,
                 std::abs(contact.tangential_offset()((dim - 1) * i) - 0.02));
    }
    check(offset_error < 1e-15, "prescribed: offsets = B u_D", offset_error);
    check(bound_error < 1e-15, "prescribed: c = gap - offset", bound_error);
    check(contact.normal_matrix().n_nonzero_elements() == 0 ||
            contact.normal_matrix().linfty_norm() == 0,
          "prescribed: no free dof in B",
          contact.normal_matrix().linfty_norm());
  }
  {
    auto body = make_unit_box<dim>("box", 0.5, 2, degree);
    body->setup();
    Tensor<1, dim> up;
    up[dim - 1] = 1;
    contact::ContactPair<dim> pair;
    pair.name            = "far";
    pair.slave_boundary  = bottom;
    pair.search_distance = 0.1;
    pair.obstacle =
      std::make_shared<contact::PlaneObstacle<dim>>(Point<dim>(), up);
    bool thrown = false;
    try
    {
      contact::ContactDiscretization<dim> contact({body.get()}, {pair});
    }
    catch (const std::exception &e)
    {
      thrown = std::string(e.what()).find("no slave node found the master") !=
               std::string::npos;
    }
    check(thrown, "out of reach: error", thrown);
  }
}

int
main()
{
  try
  {
    run<2>(1);
    run<2>(2);
    run<3>(1);
    run<3>(2);
  }
  catch (const std::exception &e)
  {
    std::cerr << "exception: " << e.what() << std::endl;
    return 1;
  }
  return test_tools::finish();
}
