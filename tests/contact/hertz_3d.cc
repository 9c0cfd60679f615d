// Hertz contact in 3D through the dual route, library level: the lower half
// of a sphere of radius R (modelled as a quarter, with the symmetry planes
// x = 0 and y = 0), pressed onto a rigid plane by a total force P (uniform
// pressure on its flat top; the closed form is evaluated for the force the
// discrete top face carries), frictionless.  Closed form with
// E* = E / (1 - nu^2): contact radius a = (3 P R / (4 E*))^(1/3), peak
// pressure p0 = 3 P / (2 pi a^2).  The contact zone is refined locally
// (hanging nodes on the contact surface).  Asserted: total contact force =
// the applied load to 1e-8 relative; the nodal pressure at the centre
// within 10% of p0; the contact radius within 5% of a plus one contact-zone
// cell (the discrete contact edge lies between two nodes).

#include <deal.II/base/function.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <fem/cholmod_solver.h>

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
    const double R = 1, E = 1000, nu = 0.3, P_nominal = 1.5;
    const double E_star = E / (1 - nu * nu);
    // refinement zone from the nominal load
    const double a_nominal = std::cbrt(3 * P_nominal * R / (4 * E_star));

    // Octant of the ball, rotated by -90 degrees about x (z -> -y): the
    // octant below the centre with x, y >= 0; then lifted to touch z = 0.
    auto tria = std::make_shared<Triangulation<3>>();
    GridGenerator::quarter_hyper_ball(*tria, Point<3>(), R);
    GridTools::rotate(Tensor<1, 3>({1., 0., 0.}), -numbers::PI / 2, *tria);
    GridTools::shift(Tensor<1, 3>({0., 0., R}), *tria);
    tria->set_all_manifold_ids(numbers::flat_manifold_id);
    for (const auto &cell : tria->active_cell_iterators())
    {
      cell->set_material_id(0);
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
        {
          const Point<3> c = cell->face(f)->center();
          if (std::abs(c[0]) < 1e-12)
            cell->face(f)->set_boundary_id(1); // symmetry x = 0
          else if (std::abs(c[1]) < 1e-12)
            cell->face(f)->set_boundary_id(2); // symmetry y = 0
          else if (std::abs(c[2] - R) < 1e-12)
            cell->face(f)->set_boundary_id(3); // loaded top
          else
          {
            cell->face(f)->set_boundary_id(0); // spherical
            // edges too: in 3D new edge midpoints must land on the sphere
            cell->face(f)->set_all_manifold_ids(0);
          }
        }
    }
    tria->set_manifold(0, SphericalManifold<3>(Point<3>(0, 0, R)));
    tria->refine_global(2);
    for (unsigned int step = 0; step < 4; ++step)
    {
      for (const auto &cell : tria->active_cell_iterators())
        if (cell->center().distance(Point<3>()) <
            1.5 * a_nominal + cell->diameter())
          cell->set_refine_flag();
      tria->execute_coarsening_and_refinement();
    }
    double h_contact = 1e300;
    for (const auto &cell : tria->active_cell_iterators())
      if (cell->center().distance(Point<3>()) < a_nominal)
        h_contact = std::min(h_contact, cell->diameter());

    fem::ElasticBody<3> body("half sphere",
                             tria,
                             1,
                             {{0, fem::IsotropicMaterial(E, nu)}});
    const auto          zero = std::make_shared<Functions::ZeroFunction<3>>(3);
    ComponentMask       x_only(3, false), y_only(3, false);
    x_only.set(0, true);
    y_only.set(1, true);
    body.set_dirichlet_conditions({{1, x_only, zero}, {2, y_only, zero}});
    // total force P on the full top disc pi R^2
    body.set_traction_conditions(
      {{3,
        std::make_shared<Functions::ConstantFunction<3>>(
          std::vector<double>{0., 0., -P_nominal / (numbers::PI * R * R)})}});
    body.setup();
    body.assemble();

    contact::ContactPair<3> pair;
    pair.name            = "sphere-plane";
    pair.slave_boundary  = 0;
    pair.search_distance = 0.1 * R;
    pair.obstacle =
      std::make_shared<contact::PlaneObstacle<3>>(Point<3>(),
                                                  Tensor<1, 3>({0., 0., 1.}));
    contact::ContactDiscretization<3> contact({&body}, {pair});
    contact::DualProblem<3>           dual(
      {&body}, contact, [] { return std::make_unique<fem::CholmodSolver>(); });
    qp::SolverParameters parameters;
    parameters.solver         = "mprgp";
    parameters.tolerance      = 1e-10;
    parameters.max_iterations = 100000;
    contact::ContactSolver<3> solver(dual, parameters, {}, {});
    const auto                result = solver.solve();

    // The closed form for the load actually applied: the flat top of the
    // mesh is a polygon slightly smaller than the quarter disc.
    const double load  = -body.applied_force()[2];
    const double P     = 4 * load;
    const double a     = std::cbrt(3 * P * R / (4 * E_star));
    const double p0    = 3 * P / (2 * numbers::PI * a * a);
    double       force = 0, peak = 0, radius = 0;
    for (unsigned int i = 0; i < contact.n_nodes(); ++i)
    {
      const auto  &node = contact.nodes()[i];
      const double r    = std::hypot(node.position[0], node.position[1]);
      force += result.lambda(i);
      if (r < 1e-12)
        peak = result.lambda(i) / node.weight;
      if (result.lambda(i) > 1e-10 * P)
        radius = std::max(radius, r);
    }
    std::cout << "a = " << a << ", p0 = " << p0 << ", h in the contact zone "
              << h_contact << ", cells " << tria->n_active_cells() << ", dofs "
              << body.n_dofs() << ", contact nodes " << contact.n_nodes()
              << ", " << result.reason << " in "
              << result.qp_statistics[0].iterations << " iterations"
              << std::endl;
    check(result.converged, "converged", result.converged);
    check(std::abs(force - load) < 1e-8 * load,
          "total contact force / load - 1",
          force / load - 1);
    check(std::abs(peak - p0) < 0.1 * p0,
          "peak pressure / p0 - 1",
          peak / p0 - 1);
    check(std::abs(radius - a) < 0.05 * a + h_contact,
          "contact radius / a - 1",
          radius / a - 1);
  }
  catch (const std::exception &e)
  {
    std::cerr << "exception: " << e.what() << std::endl;
    return 1;
  }
  return test_tools::finish();
}
