// The Trilinos stiffness solvers (MUMPS through Amesos, AMG-preconditioned
// CG) against CHOLMOD, under mpirun with 1 and 2 processes: a 3D bar (Q2,
// distorted cells, clamped at one end, traction at the other) and a 2D
// plate (Q1), each on a parallel::shared::Triangulation partitioned by METIS
// so that the rows of a process are its subdomain's dofs.
//  - MUMPS: relative difference to CHOLMOD < 1e-10 (both direct; measured
//    5e-13 in 3D, the round-off of a matrix with condition ~1e5 to 1e6);
//  - AMG-CG to a relative residual of 1e-12: relative difference < 1e-8
//    (the error is bounded by cond(K) times the residual);
//  - the whole solution on every process (gathered), the same on all of
//    them; a second solve reuses the factorization / hierarchy;
//  - the rows default to an even split when none are given, and the
//    distributed interface (Trilinos vectors) gives the same solution;
//  - AMG-CG with an iteration limit of 2 reports that it did not converge;
//  - CHOLMOD (serial) gives every process the same bits, the Trilinos
//    solvers say they are distributed, `Solver = automatic' is cholmod and
//    util::processes_on_this_machine() counts every process of mpirun.

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <fem/cholmod_solver.h>
#include <fem/elastic_body.h>
#include <fem/trilinos_solver.h>
#include <util/machine.h>

#include <iostream>
#include <sstream>

#include "../test_tools.h"

using namespace dealii;
using namespace dualcontact;

namespace
{
  /** Largest difference of @p u over the processes (0 if all agree). */
  double
  spread_over_processes(const Vector<double> &u)
  {
    Vector<double> min(u), max(u);
    Utilities::MPI::min(ArrayView<const double>(u.begin(), u.size()),
                        MPI_COMM_WORLD,
                        ArrayView<double>(min.begin(), min.size()));
    Utilities::MPI::max(ArrayView<const double>(u.begin(), u.size()),
                        MPI_COMM_WORLD,
                        ArrayView<double>(max.begin(), max.size()));
    max -= min;
    return max.linfty_norm();
  }

  template <int dim>
  void
  check_body(const std::string &name, const unsigned int degree)
  {
    auto tria = std::make_shared<parallel::shared::Triangulation<dim>>(
      MPI_COMM_WORLD,
      Triangulation<dim>::none,
      false,
      parallel::shared::Triangulation<dim>::partition_metis);
    // 3D: 8 x 3 x 3 Q2 cells (2499 dofs); 2D: 60 x 20 Q1 cells (2562
    // dofs): both above deal.II's ML coarse-grid size (2000), so that AMG
    // has more than one level and CG iterates
    std::vector<unsigned int> subdivisions(dim, dim == 3 ? 3 : 20);
    subdivisions[0] = dim == 3 ? 8 : 60;
    Point<dim> upper;
    for (unsigned int d = 0; d < dim; ++d)
      upper[d] = d == 0 ? 4 : 1;
    GridGenerator::subdivided_hyper_rectangle(
      *tria, subdivisions, Point<dim>(), upper, true);
    for (const auto &cell : tria->active_cell_iterators())
      cell->set_material_id(0);
    // the same distortion on every process (fixed seed)
    GridTools::distort_random(0.2, *tria, true, 7);
    const fem::IsotropicMaterial material(2e11, 0.3);
    fem::ElasticBody<dim>        body(name, tria, degree, {{0, material}});
    body.set_dirichlet_conditions(
      {{0,
        ComponentMask(dim, true),
        std::make_shared<Functions::ZeroFunction<dim>>(dim)}});
    std::vector<double> traction(dim, 1e6);
    traction[1] = -2e6;
    body.set_traction_conditions(
      {{1, std::make_shared<Functions::ConstantFunction<dim>>(traction)}});
    body.setup();
    body.assemble();
    std::cout << name << ": " << body.n_dofs() << " dofs, "
              << body.dof_handler().n_locally_owned_dofs()
              << " owned by this process" << std::endl;

    fem::CholmodSolver cholmod;
    Vector<double>     reference;
    body.solve(cholmod, reference);
    // CHOLMOD under MPI: every process factorizes the whole matrix and
    // gets the same bits (`Solver = automatic' relies on it)
    test_tools::check(!cholmod.is_distributed() &&
                        spread_over_processes(reference) == 0,
                      name + ", cholmod: serial, the same solution on every "
                             "process",
                      spread_over_processes(reference));

    for (const auto method : {fem::TrilinosSolver::Method::mumps,
                              fem::TrilinosSolver::Method::amg_cg})
    {
      fem::TrilinosSolver::Parameters parameters;
      parameters.method = method;
      fem::TrilinosSolver solver(parameters);
      test_tools::check(solver.is_distributed(),
                        name + ", " + solver.name() + ": distributed",
                        solver.is_distributed());
      solver.set_block_size(dim);
      solver.set_locally_owned_rows(body.dof_handler().locally_owned_dofs());
      Vector<double> u;
      body.solve(solver, u);
      Vector<double> again;
      solver.solve(again, body.load_vector());
      body.distribute(again);
      const double spread = spread_over_processes(u);
      u -= reference;
      again -= reference;
      const double bound =
        method == fem::TrilinosSolver::Method::mumps ? 1e-10 : 1e-8;
      const std::string what = name + ", " + solver.name();
      test_tools::check(u.l2_norm() / reference.l2_norm() < bound,
                        what + ": relative difference to CHOLMOD",
                        u.l2_norm() / reference.l2_norm());
      test_tools::check(again.l2_norm() / reference.l2_norm() < bound,
                        what + ": second solve, relative difference",
                        again.l2_norm() / reference.l2_norm());
      test_tools::check(spread == 0,
                        what + ": spread of the solution over processes",
                        spread);
      test_tools::check(solver.statistics().n_solves == 2,
                        what + ": solves counted",
                        solver.statistics().n_solves);
      test_tools::check(solver.locally_owned_rows() ==
                          body.dof_handler().locally_owned_dofs(),
                        what + ": rows = the subdomain's dofs",
                        solver.locally_owned_rows().n_elements());
      if (method == fem::TrilinosSolver::Method::amg_cg)
        test_tools::check(solver.statistics().iterations > 0 &&
                            solver.statistics().iterations < 1000,
                          what + ": CG iterations",
                          solver.statistics().iterations);
    }

    // rows split evenly (no partition given), the distributed interface
    {
      fem::TrilinosSolver::Parameters parameters;
      fem::TrilinosSolver             solver(parameters);
      solver.initialize(body.stiffness_matrix());
      const IndexSet &rows = solver.locally_owned_rows();
      const auto      n_rows =
        Utilities::MPI::sum(rows.n_elements(), MPI_COMM_WORLD);
      test_tools::check(rows.is_contiguous() && n_rows == body.n_dofs(),
                        name + ", even split: rows of all processes",
                        n_rows);
      TrilinosWrappers::MPI::Vector b(rows, MPI_COMM_WORLD), x(b);
      for (const auto row : rows)
        b(row) = body.load_vector()(row);
      b.compress(VectorOperation::insert);
      solver.solve(x, b);
      double local = 0;
      for (const auto row : rows)
      {
        const double value =
          body.constraints().is_constrained(row) ? 0. : x(row) - reference(row);
        local += value * value;
      }
      const double error =
        std::sqrt(Utilities::MPI::sum(local, MPI_COMM_WORLD)) /
        reference.l2_norm();
      test_tools::check(error < 1e-10,
                        name + ", distributed interface: relative difference",
                        error);
    }

    // AMG-CG that cannot converge says so
    {
      fem::TrilinosSolver::Parameters parameters;
      parameters.method            = fem::TrilinosSolver::Method::amg_cg;
      parameters.cg_max_iterations = 2;
      fem::TrilinosSolver solver(parameters);
      std::string         message;
      try
      {
        Vector<double> u;
        body.solve(solver, u);
      }
      catch (const std::exception &e)
      {
        // deal.II wraps the text of its messages: compare without breaks
        std::istringstream words(e.what());
        for (std::string word; words >> word;)
          message += word + " ";
      }
      test_tools::check(message.find("did not converge") != std::string::npos &&
                          message.find("CG max iterations") !=
                            std::string::npos,
                        name + ", amg with 2 iterations: error reported",
                        message.empty() ? "(none)" : "yes");
    }
  }
} // namespace


int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  try
  {
    check_body<3>("3D bar, Q2", 2);
    check_body<2>("2D plate, Q1", 1);
    // `Solver = automatic' is cholmod on any number of processes, and
    // `Memory limit' counts its copies: mpirun here puts every process on
    // this machine
    test_tools::check(fem::StiffnessSolver::resolved_name("automatic") ==
                        "cholmod",
                      "Solver = automatic",
                      fem::StiffnessSolver::resolved_name("automatic"));
    test_tools::check(util::processes_on_this_machine() ==
                        Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD),
                      "processes on this machine = processes",
                      util::processes_on_this_machine());
  }
  catch (const std::exception &e)
  {
    std::cout << "  FAIL exception: " << e.what() << std::endl;
    ++test_tools::failures;
  }
  // every process must pass
  const int failures =
    Utilities::MPI::sum(test_tools::failures, MPI_COMM_WORLD);
  test_tools::failures = failures;
  return test_tools::finish();
}
