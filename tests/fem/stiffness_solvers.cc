// The stiffness solvers agree: CHOLMOD with every ordering and UMFPACK give
// the same displacement (relative difference < 1e-10) on a 3D elasticity
// system with mixed conditions; repeated solves reuse the factorization; a
// body without Dirichlet conditions (singular K) is reported as not positive
// definite instead of returning garbage.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <fem/cholmod_solver.h>
#include <fem/elastic_body.h>
#include <fem/umfpack_solver.h>

#include <iostream>

using namespace dealii;
using namespace dualcontact;

int
main()
{
  int failures = 0;
  try
  {
    auto tria = std::make_shared<Triangulation<3>>();
    GridGenerator::subdivided_hyper_rectangle(
      *tria, {4, 2, 2}, Point<3>(), Point<3>(2, 1, 1), true);
    for (const auto &cell : tria->active_cell_iterators())
      cell->set_material_id(0);
    GridTools::distort_random(0.2, *tria, true, 7);
    const fem::IsotropicMaterial material(2e11, 0.3);
    fem::ElasticBody<3>          body("bar", tria, 2, {{0, material}});
    body.set_dirichlet_conditions(
      {{0,
        ComponentMask(3, true),
        std::make_shared<Functions::ZeroFunction<3>>(3)}});
    body.set_traction_conditions(
      {{1,
        std::make_shared<Functions::ConstantFunction<3>>(
          std::vector<double>{1e6, -2e6, 3e5})}});
    body.setup();
    body.assemble();

    fem::UmfpackSolver reference_solver;
    Vector<double>     reference;
    body.solve(reference_solver, reference);

    for (const auto ordering :
         {fem::CholmodSolver::Ordering::automatic,
          fem::CholmodSolver::Ordering::amd,
          fem::CholmodSolver::Ordering::metis,
          fem::CholmodSolver::Ordering::nested_dissection})
    {
      fem::CholmodSolver solver(ordering);
      Vector<double>     u;
      body.solve(solver, u);
      Vector<double> again;
      solver.solve(again, body.load_vector());
      body.distribute(again);
      u -= reference;
      again -= reference;
      const double diff       = u.l2_norm() / reference.l2_norm();
      const double diff_again = again.l2_norm() / reference.l2_norm();
      const bool   ok         = diff < 1e-10 && diff_again < 1e-10 &&
                      solver.statistics().n_solves == 2 &&
                      solver.statistics().factor_nonzeros > 0;
      std::cout << (ok ? "  ok   " : "  FAIL ") << "CHOLMOD ordering "
                << static_cast<int>(ordering) << ": relative difference "
                << diff << " (second solve " << diff_again << "), nnz(L) "
                << solver.statistics().factor_nonzeros << std::endl;
      failures += ok ? 0 : 1;
    }

    // Floating: no Dirichlet condition.
    fem::ElasticBody<3> floating("floating", tria, 1, {{0, material}});
    floating.setup();
    floating.assemble();
    bool               thrown = false;
    fem::CholmodSolver solver;
    try
    {
      solver.initialize(floating.stiffness_matrix());
    }
    catch (const std::exception &e)
    {
      thrown = std::string(e.what()).find("not positive definite") !=
               std::string::npos;
    }
    std::cout << (thrown ? "  ok   " : "  FAIL ")
              << "singular K reported as not positive definite" << std::endl;
    failures += thrown ? 0 : 1;
  }
  catch (const std::exception &e)
  {
    std::cerr << "exception: " << e.what() << std::endl;
    return 1;
  }
  std::cout << (failures == 0 ? "all checks passed" : "FAILED") << std::endl;
  return failures == 0 ? 0 : 1;
}
