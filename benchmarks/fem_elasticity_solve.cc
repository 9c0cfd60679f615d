// Times the phases of one linear elasticity solve on a cantilever box
// [0,2] x [0,1] (x [0,1]) with (2N, N[, N]) Q1/Q2 cells, clamped at x = 0 and
// loaded by a traction at x = 2: dof set-up, assembly, factorization, one
// solve, and the peak resident memory of the process.
//
//   bench_fem_elasticity_solve DIM N [DEGREE=1]
//                          [SOLVER=cholmod|cholmod-amd|cholmod-metis|umfpack]
//
// Prints one line: dim degree cells dofs setup assembly factorize solve
// nnz(L) GFlop(factorization) peak_MB.  scripts/bench_elasticity runs it over a
// range of sizes, one process per size so that the peak memory is that size's.

#include <deal.II/base/timer.h>
#include <deal.II/grid/grid_generator.h>
#include <util/blas_kernels.h>

#include <fem/cholmod_solver.h>
#include <fem/elastic_body.h>
#include <fem/umfpack_solver.h>

#include <sys/resource.h>

#include <iomanip>
#include <iostream>

using namespace dealii;
using namespace dualcontact;

template <int dim>
void
run(const unsigned int n, const unsigned int degree, const std::string &name)
{
  Timer                     timer;
  auto                      tria = std::make_shared<Triangulation<dim>>();
  std::vector<unsigned int> subdivisions(dim, n);
  subdivisions[0] = 2 * n;
  Point<dim> p2;
  p2[0] = 2;
  for (unsigned int d = 1; d < dim; ++d)
    p2[d] = 1;
  GridGenerator::subdivided_hyper_rectangle(
    *tria, subdivisions, Point<dim>(), p2, true);
  for (const auto &cell : tria->active_cell_iterators())
    cell->set_material_id(0);
  fem::ElasticBody<dim> body("box",
                             tria,
                             degree,
                             {{0, fem::IsotropicMaterial(2e11, 0.3)}});
  body.set_dirichlet_conditions(
    {{0,
      ComponentMask(dim, true),
      std::make_shared<Functions::ZeroFunction<dim>>(dim)}});
  std::vector<double> traction(dim, 0.);
  traction[dim - 1] = -1e6;
  body.set_traction_conditions(
    {{1, std::make_shared<Functions::ConstantFunction<dim>>(traction)}});
  body.setup();
  const double t_setup = timer.wall_time();
  timer.restart();
  body.assemble();
  const double t_assemble = timer.wall_time();

  std::unique_ptr<fem::StiffnessSolver> solver;
  if (name == "umfpack")
    solver = std::make_unique<fem::UmfpackSolver>();
  else if (name == "cholmod")
    solver = std::make_unique<fem::CholmodSolver>();
  else // cholmod-<ordering>
    solver = std::make_unique<fem::CholmodSolver>(
      fem::CholmodSolver::ordering_names.value(name.substr(8)));
  timer.restart();
  solver->initialize(body.stiffness_matrix());
  const double   t_factorize = timer.wall_time();
  Vector<double> u;
  timer.restart();
  solver->solve(u, body.load_vector());
  const double t_solve = timer.wall_time();

  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  std::cout << dim << ' ' << degree << ' ' << tria->n_active_cells() << ' '
            << body.n_dofs() << std::fixed << std::setprecision(3) << ' '
            << t_setup << ' ' << t_assemble << ' ' << t_factorize << ' '
            << t_solve << ' ' << std::setprecision(0)
            << solver->statistics().factor_nonzeros << ' '
            << std::setprecision(1) << solver->statistics().factor_flops / 1e9
            << ' ' << usage.ru_maxrss / 1024. << std::endl;
}

int
main(int argc, char **argv)
{
  // OpenBLAS' fast kernels on CPUs it does not recognise
  (void)dualcontact::util::blas_kernel_choice();
  if (argc < 3)
  {
    std::cerr << "usage: bench_fem_elasticity_solve DIM N [DEGREE] [SOLVER]\n";
    return 1;
  }
  const int          dim    = std::stoi(argv[1]);
  const unsigned int n      = std::stoi(argv[2]);
  const unsigned int degree = argc > 3 ? std::stoi(argv[3]) : 1;
  const std::string  solver = argc > 4 ? argv[4] : "cholmod";
  try
  {
    if (dim == 2)
      run<2>(n, degree, solver);
    else
      run<3>(n, degree, solver);
  }
  catch (const std::exception &e)
  {
    std::cerr << e.what() << std::endl;
    return 1;
  }
  return 0;
}
