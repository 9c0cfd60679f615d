// Hanging nodes on the slave surface (3D): a unit cube, its cells at the
// bottom with x < 1/2 refined once, so the bottom face (the slave surface)
// has two hanging nodes on the edge x = 1/2, pressed by a uniform traction
// p on its top onto a rigid frictionless plane, with rollers on x = 0 and
// y = 0 (it floats vertically: SMALSE-M).  The exact solution is uniaxial
// stress (linear, in the FE space), so the contact pressure is p at every
// node.  Asserted: the hanging nodes are no contact nodes (16 of the 18
// vertices of the bottom face; no contact node has a constrained vertical
// dof), the area weights are the integrals of the true (constrained) basis
// functions (their sum is the area 1, and p_i = lambda_i / w_i = p at every
// node to 1e-8 relative), and the total force is p.  With the hanging nodes
// as contact nodes their rows repeat the parents' (F singular) and the
// multipliers split arbitrarily between a hanging node and its parents.

#include <deal.II/base/function.h>

#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <fem/cholmod_solver.h>

#include "unit_box.h"
#include <test_tools.h>

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

int
main()
{
  try
  {
    const double  p    = 2e6;
    auto          body = make_unit_box<3>("cube",
                                 0,
                                 2,
                                 1,
                                 1e9,
                                 [](const Point<3> &c)
                                 { return c[0] < 0.5 && c[2] < 0.5; });
    const auto    zero = std::make_shared<Functions::ZeroFunction<3>>(3);
    ComponentMask x_only(3, false), y_only(3, false);
    x_only.set(0, true);
    y_only.set(1, true);
    body->set_dirichlet_conditions({{0, x_only, zero}, {2, y_only, zero}});
    body->set_traction_conditions(
      {{5,
        std::make_shared<Functions::ConstantFunction<3>>(
          std::vector<double>{0., 0., -p})}});
    body->setup();
    body->assemble();

    contact::ContactPair<3> pair;
    pair.name            = "cube-plane";
    pair.slave_boundary  = 4;
    pair.search_distance = 0.1;
    pair.obstacle =
      std::make_shared<contact::PlaneObstacle<3>>(Point<3>(),
                                                  Tensor<1, 3>({0., 0., 1.}));
    contact::ContactDiscretization<3> contact({body.get()}, {pair});

    unsigned int n_hanging = 0;
    for (unsigned int i = 0; i < contact.n_nodes(); ++i)
      if (body->constraints().is_constrained(contact.nodes()[i].dofs[2]))
        ++n_hanging;
    check(contact.n_nodes() == 16,
          "contact nodes (18 vertices, 2 hanging)",
          contact.n_nodes());
    check(n_hanging == 0, "contact nodes with a hanging dof", n_hanging);
    double area = 0;
    for (const auto &node : contact.nodes())
      area += node.weight;
    check(std::abs(area - 1) < 1e-12, "sum of the weights (area 1)", area);

    contact::DualProblem<3> dual(
      {body.get()},
      contact,
      [] { return std::make_unique<fem::CholmodSolver>(); });
    qp::SolverParameters parameters;
    parameters.solver         = "mprgp";
    parameters.tolerance      = 1e-12;
    parameters.max_iterations = 100000;
    contact::ContactSolver<3> solver(dual, parameters, {}, {});
    const auto                result = solver.solve();
    check(result.converged, "converged", result.reason);

    double force = 0, worst = 0;
    for (unsigned int i = 0; i < contact.n_nodes(); ++i)
    {
      const auto &node = contact.nodes()[i];
      force += result.lambda(i);
      worst = std::max(worst, std::abs(result.lambda(i) / node.weight / p - 1));
      std::cout << "    node (" << node.position << "): w = " << node.weight
                << ", p_i / p = " << result.lambda(i) / node.weight / p
                << std::endl;
    }
    check(worst < 1e-8, "max |p_i / p - 1|", worst);
    check(std::abs(force / p - 1) < 1e-8, "total force / p", force / p);
  }
  catch (const std::exception &e)
  {
    std::cerr << "Exception: " << e.what() << std::endl;
    return 1;
  }
  return test_tools::finish();
}
