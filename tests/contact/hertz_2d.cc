// Hertz contact in 2D (plane strain) through the dual route, library level:
// the lower half of a cylinder of radius R (modelled as a quarter, with the
// symmetry plane x = 0), pressed onto a rigid plane by a total force P per
// unit thickness (uniform pressure on its flat top), frictionless.  Closed
// form with E* = E / (1 - nu^2): half-width a = sqrt(4 P R / (pi E*)), peak
// pressure p0 = 2 P / (pi a).  The contact zone is refined locally (hanging
// nodes on the contact surface).  Asserted: total contact force = P/2 (the
// half model) to 1e-8 relative; the nodal pressure at x = 0 within 5% of p0;
// the contact half-width within one contact-zone cell of a; the pressure
// within 10% of p0 of the closed form at every node with |x| < 0.8 a.

#include <deal.II/base/function.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <fem/cholmod_solver.h>

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace dualcontact;

int
main()
{
  int failures = 0;
  try
  {
    const double R = 1, E = 1000, nu = 0.3, P = 2;
    const double E_star = E / (1 - nu * nu);
    const double a      = std::sqrt(4 * P * R / (numbers::PI * E_star));
    const double p0     = 2 * P / (numbers::PI * a);

    // Quarter disc in the first quadrant, rotated by -90 degrees to the
    // lower right quadrant, then lifted so that it touches y = 0 at x = 0.
    auto tria = std::make_shared<Triangulation<2>>();
    GridGenerator::quarter_hyper_ball(*tria, Point<2>(), R);
    GridTools::rotate(-numbers::PI / 2, *tria);
    GridTools::shift(Tensor<1, 2>({0., R}), *tria);
    tria->set_all_manifold_ids(numbers::flat_manifold_id);
    for (const auto &cell : tria->active_cell_iterators())
    {
      cell->set_material_id(0);
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
        {
          const Point<2> c = cell->face(f)->center();
          if (std::abs(c[0]) < 1e-12)
            cell->face(f)->set_boundary_id(1); // symmetry x = 0
          else if (std::abs(c[1] - R) < 1e-12)
            cell->face(f)->set_boundary_id(2); // loaded top
          else
          {
            cell->face(f)->set_boundary_id(0); // curved
            cell->face(f)->set_manifold_id(0);
          }
        }
    }
    tria->set_manifold(0, SphericalManifold<2>(Point<2>(0, R)));
    tria->refine_global(3);
    for (unsigned int step = 0; step < 5; ++step)
    {
      for (const auto &cell : tria->active_cell_iterators())
        if (cell->center().distance(Point<2>(0, 0)) <
            3 * a + 2 * cell->diameter())
          cell->set_refine_flag();
      tria->execute_coarsening_and_refinement();
    }
    double h_contact = 1e300;
    for (const auto &cell : tria->active_cell_iterators())
      if (cell->center().distance(Point<2>(0, 0)) < a)
        h_contact = std::min(h_contact, cell->diameter());

    fem::ElasticBody<2> body("half cylinder",
                             tria,
                             1,
                             {{0, fem::IsotropicMaterial(E, nu)}});
    ComponentMask       x_only(2, false);
    x_only.set(0, true);
    body.set_dirichlet_conditions(
      {{1, x_only, std::make_shared<Functions::ZeroFunction<2>>(2)}});
    // total force P on the full top 2R: pressure P / (2R)
    body.set_traction_conditions(
      {{2,
        std::make_shared<Functions::ConstantFunction<2>>(
          std::vector<double>{0., -P / (2 * R)})}});
    body.setup();
    body.assemble();

    contact::ContactPair<2> pair;
    pair.name            = "cylinder-plane";
    pair.slave_boundary  = 0;
    pair.search_distance = 0.2 * R;
    pair.obstacle =
      std::make_shared<contact::PlaneObstacle<2>>(Point<2>(),
                                                  Tensor<1, 2>({0., 1.}));
    contact::ContactDiscretization<2> contact({&body}, {pair});
    contact::DualProblem<2>           dual(
      {&body}, contact, [] { return std::make_unique<fem::CholmodSolver>(); });
    qp::SolverParameters parameters;
    parameters.solver         = "mprgp";
    parameters.tolerance      = 1e-10;
    parameters.max_iterations = 100000;
    contact::ContactSolver<2> solver(dual, parameters, {}, {});
    const auto                result = solver.solve();

    double force = 0, peak = 0, half_width = 0, worst = 0;
    for (unsigned int i = 0; i < contact.n_nodes(); ++i)
    {
      const auto  &node     = contact.nodes()[i];
      const double pressure = result.lambda(i) / node.weight;
      const double x        = node.position[0];
      force += result.lambda(i);
      if (x < 1e-12)
        peak = pressure;
      if (result.lambda(i) > 1e-10 * P)
        half_width = std::max(half_width, x);
      if (x < 0.8 * a && x > 1e-12)
        worst = std::max(
          worst, std::abs(pressure - p0 * std::sqrt(1 - x * x / (a * a))) / p0);
    }
    std::cout << "a = " << a << ", p0 = " << p0 << ", h in the contact zone "
              << h_contact << ", contact nodes " << contact.n_nodes() << ", "
              << result.reason << " in " << result.qp_statistics[0].iterations
              << " iterations" << std::endl;
    const auto check =
      [&](const bool ok, const std::string &what, const double value)
    {
      std::cout << (ok ? "  ok   " : "  FAIL ") << what << ": " << value
                << std::endl;
      failures += ok ? 0 : 1;
    };
    check(result.converged, "converged", result.converged);
    check(std::abs(force - P / 2) < 1e-8 * P,
          "total force / (P/2) - 1",
          force / (P / 2) - 1);
    check(std::abs(peak - p0) < 0.05 * p0,
          "peak pressure / p0 - 1",
          peak / p0 - 1);
    check(std::abs(half_width - a) < h_contact,
          "half-width / a - 1",
          half_width / a - 1);
    check(worst < 0.1, "max |p - p_Hertz| / p0 for |x| < 0.8 a", worst);
  }
  catch (const std::exception &e)
  {
    std::cerr << "exception: " << e.what() << std::endl;
    return 1;
  }
  std::cout << (failures == 0 ? "all checks passed" : "FAILED") << std::endl;
  return failures == 0 ? 0 : 1;
}
