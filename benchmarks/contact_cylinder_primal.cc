// Benchmark B5 in the thesis' own formulation (Pospisil 2015, section
// 3.2.2, table 11): the PRIMAL bound-constrained QP of a floating elastic
// disc pressed by gravity into a rigid 90-degree corner,
//
//   minimize 1/2 u'Ku - f'u  subject to  u_x,i >= -x_i, u_y,i >= -y_i
//   (every boundary node i),
//
// K the stiffness matrix of the disc without any Dirichlet condition (three
// zero eigenvalues: symmetric positive SEMIdefinite, the MPRGPS case), in
// the frame rotated by -pi/4 in which both walls are coordinate lines: the
// walls are x = 0 and y = 0, the disc of radius R is centred at (R, R) and
// touches both, and gravity points along -(1, 1)/sqrt(2).  The application
// (inputs/cylinder.prm) solves the same scene through the dual with
// SMALSE-M; this program is what the thesis' table 11 measured.
//
//   bench_contact_cylinder_primal E SOLVER [TOLERANCE=1e-4]
//       [MAX_ITERATIONS=10000] [REFINEMENTS=3] [RADIUS=2.18]
//       [DENSITY=7820] [POISSON=0.3]
//
// E [Pa], SOLVER one of the qp factory's names (mprgp = MPRGPS here, as the
// Hessian is singular).  Table 14's settings (the qp defaults): x0 = 0,
// alpha_bar = 1.95 / lambda_max, Gamma = 1, PBBf/K = 10, SPG-QP/m = 10,
// gamma = 0.1, sigma2 = 0.9999, APGD/L factor = 1 (L = lambda_max); the
// stopping test is
// ||g^P(x)|| <= TOLERANCE ||b||.  lambda_max is computed exactly (dense
// symmetric eigenvalues, the mesh is small) and given to the solvers, as
// are the regular smallest eigenvalue and condition number for the report.
//
// Prints one JSON object: the scene (dofs, ||b||, spectrum, number of
// bounds), the solver's statistics record (iterations by kind, Hessian
// products, reason, KKT residuals) and the number of active bounds.

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <util/blas_kernels.h>

#include <fem/elastic_body.h>
#include <qp/solver_factory.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>

using namespace dealii;
using namespace dualcontact;

int
main(int argc, char **argv)
{
  // OpenBLAS' fast kernels on CPUs it does not recognise
  (void)dualcontact::util::blas_kernel_choice();
  if (argc < 3)
  {
    std::cerr << "usage: bench_contact_cylinder_primal E SOLVER [TOLERANCE] "
                 "[MAX_ITERATIONS] [REFINEMENTS] [RADIUS] [DENSITY] "
                 "[POISSON]\n";
    return 1;
  }
  try
  {
    const double       youngs_modulus = std::stod(argv[1]);
    const std::string  solver_name    = argv[2];
    const double       tolerance      = argc > 3 ? std::stod(argv[3]) : 1e-4;
    const unsigned int max_iterations = argc > 4 ? std::stoi(argv[4]) : 10000;
    const unsigned int refinements    = argc > 5 ? std::stoi(argv[5]) : 3;
    const double       radius         = argc > 6 ? std::stod(argv[6]) : 2.18;
    const double       density        = argc > 7 ? std::stod(argv[7]) : 7820.;
    const double       poisson        = argc > 8 ? std::stod(argv[8]) : 0.3;
    const double       gravity        = 9.81;

    auto tria = std::make_shared<Triangulation<2>>();
    GridGenerator::hyper_ball(*tria, Point<2>(radius, radius), radius);
    tria->refine_global(refinements);
    for (const auto &cell : tria->active_cell_iterators())
      cell->set_material_id(0);
    fem::ElasticBody<2> body(
      "disc", tria, 1, {{0, fem::IsotropicMaterial(youngs_modulus, poisson)}});
    const double component = -density * gravity / std::sqrt(2.);
    body.set_body_force(std::make_shared<Functions::ConstantFunction<2>>(
      std::vector<double>{component, component}));
    body.setup();
    body.assemble();
    const SparseMatrix<double> &K = body.stiffness_matrix();
    const unsigned int          n = body.n_dofs();

    // spectrum (dense, n is a few hundred)
    LAPACKFullMatrix<double> dense(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (auto it = K.begin(i); it != K.end(i); ++it)
        dense(i, it->column()) = it->value();
    Vector<double>     eigenvalue_vector;
    FullMatrix<double> eigenvectors;
    dense.compute_eigenvalues_symmetric(
      -1e300, 1e300, 0., eigenvalue_vector, eigenvectors);
    std::vector<double> eigenvalues(eigenvalue_vector.begin(),
                                    eigenvalue_vector.end());
    std::sort(eigenvalues.begin(), eigenvalues.end());
    const double lambda_max = eigenvalues.back();
    // three zero eigenvalues (rigid-body modes of the plane)
    const double lambda_min_regular = eigenvalues[3];

    // bounds at the boundary nodes: the walls x = 0 and y = 0
    std::vector<Point<2>> support(n);
    DoFTools::map_dofs_to_support_points(body.mapping(),
                                         body.dof_handler(),
                                         support);
    const IndexSet boundary =
      DoFTools::extract_boundary_dofs(body.dof_handler(),
                                      ComponentMask(),
                                      std::set<types::boundary_id>{0});
    auto set = std::make_shared<qp::SeparableSet<Vector<double>>>();
    std::vector<unsigned int> component_of(n);
    {
      std::vector<types::global_dof_index> dofs(body.fe().n_dofs_per_cell());
      for (const auto &cell : body.dof_handler().active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int k = 0; k < dofs.size(); ++k)
          component_of[dofs[k]] = body.fe().system_to_component_index(k).first;
      }
    }
    unsigned int n_bounds = 0;
    for (const auto dof : boundary)
    {
      set->add_bound(dof, -support[dof][component_of[dof]]);
      ++n_bounds;
    }
    Vector<double> layout(n);
    set->finalize(layout);

    qp::Problem<Vector<double>> problem;
    problem.hessian = [&K](Vector<double> &dst, const Vector<double> &src)
    { K.vmult(dst, src); };
    problem.b            = body.load_vector();
    problem.constraints  = set;
    problem.lambda_max   = lambda_max;
    problem.semidefinite = true;

    qp::SolverParameters prm;
    prm.solver         = solver_name;
    prm.tolerance      = tolerance;
    prm.max_iterations = max_iterations;
    // the thesis stops only on the iteration limit (table 11's "*")
    prm.stagnation_window = 0;
    auto           solver = qp::create<Vector<double>>(solver_name, prm);
    Vector<double> x(n);
    const qp::SolverStatistics stats = solver->solve(problem, x);

    nlohmann::json out;
    out["youngs_modulus_Pa"]  = youngs_modulus;
    out["radius_m"]           = radius;
    out["refinements"]        = refinements;
    out["n_dofs"]             = n;
    out["n_bounds"]           = n_bounds;
    out["norm_b"]             = problem.b.l2_norm();
    out["lambda_max"]         = lambda_max;
    out["lambda_min_regular"] = lambda_min_regular;
    out["kappa_regular"]      = lambda_max / lambda_min_regular;
    out["n_zero_eigenvalues"] = static_cast<unsigned int>(
      std::count_if(eigenvalues.begin(),
                    eigenvalues.end(),
                    [&](const double v)
                    { return std::abs(v) <= 1e-10 * lambda_max; }));
    // active bounds (nodes on a wall), by the set's active-set test
    out["n_active_bounds"] = static_cast<unsigned long>(
      set->n_active_blocks(x)[static_cast<unsigned int>(qp::BlockType::bound)]);
    out["statistics"] = nlohmann::json::parse(stats.to_json(false));
    std::cout << out.dump() << std::endl;
    return stats.converged() ? 0 : 2;
  }
  catch (const std::exception &e)
  {
    std::cerr << "Error: " << e.what() << std::endl;
    return 1;
  }
}
