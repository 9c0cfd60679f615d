// fem::FactorEstimate, CHOLMOD's symbolic analysis of a sparsity pattern
// alone, gives the factor nonzeros and flops that CholmodSolver's
// factorization of the assembled matrix reports, for every ordering (the
// same pattern: the condensed stiffness pattern of a 3D body with Dirichlet
// conditions, distorted cells, Q1 and Q2), and it is cheap: its time is
// printed beside the factorization's.

#include <deal.II/base/timer.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <fem/cholmod_solver.h>
#include <fem/elastic_body.h>
#include <fem/factor_estimate.h>

#include <test_tools.h>

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

int
main()
{
  for (const unsigned int degree : {1u, 2u})
  {
    auto tria = std::make_shared<Triangulation<3>>();
    GridGenerator::subdivided_hyper_rectangle(
      *tria, {8, 4, 4}, Point<3>(), Point<3>(2, 1, 1), true);
    GridTools::distort_random(0.2, *tria, true, 7);
    for (const auto &cell : tria->active_cell_iterators())
      cell->set_material_id(0);
    const fem::IsotropicMaterial material(2e11, 0.3);
    fem::ElasticBody<3>          body("bar", tria, degree, {{0, material}});
    body.set_dirichlet_conditions(
      {{0,
        ComponentMask(3, true),
        std::make_shared<Functions::ZeroFunction<3>>(3)}});
    body.setup();
    body.assemble();
    std::cout << "Q" << degree << ", " << body.n_dofs() << " dofs" << std::endl;
    for (const auto ordering :
         {fem::CholmodSolver::Ordering::automatic,
          fem::CholmodSolver::Ordering::amd,
          fem::CholmodSolver::Ordering::metis,
          fem::CholmodSolver::Ordering::nested_dissection})
    {
      const std::string name =
        fem::CholmodSolver::ordering_names.name(ordering);
      Timer                             analysis;
      const fem::FactorEstimate::Result estimate = fem::FactorEstimate::analyze(
        body.stiffness_matrix().get_sparsity_pattern(), ordering);
      analysis.stop();
      fem::CholmodSolver solver(ordering);
      Timer              factorization;
      solver.initialize(body.stiffness_matrix());
      factorization.stop();
      const auto  &s = solver.statistics();
      const double nnz_error =
        std::abs(estimate.factor_nonzeros - s.factor_nonzeros) /
        s.factor_nonzeros;
      const double flop_error =
        std::abs(estimate.flops - s.factor_flops) / s.factor_flops;
      // the matrix may hold a few explicit zeros (cancellation in the
      // condensation) that the factorization drops and the pattern keeps
      check(nnz_error < 1e-3 && flop_error < 1e-3,
            name + ": analysis = factorization (nnz, flops relative)",
            std::to_string(nnz_error) + ", " + std::to_string(flop_error) +
              " (nnz " + std::to_string(s.factor_nonzeros) + ", analysis " +
              std::to_string(analysis.wall_time()) + " s, factorization " +
              std::to_string(factorization.wall_time()) + " s)");
      check(std::abs(estimate.n_rows - body.n_dofs()) == 0,
            name + ": order",
            estimate.n_rows);
    }
  }
  return test_tools::failures == 0 ? 0 : 1;
}
