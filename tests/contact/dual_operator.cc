// The assembled dual operator (F = W'W from the Schur factors of K on the
// contact dofs) against the implicit one (one K^# solve per product), on a
// scene that exercises every path of the assembly: a clamped lower block
// with a locally refined top (hanging nodes in B), a floating upper block
// (generalized inverse: fixing dofs dropped from the Schur complement),
// non-matching meshes, Q1 and Q2, Tresca friction (tangential rows).
// Checked, 2D and 3D:
//  - F x agrees for random x (1e-10 relative), and lambda_max(F) (1e-8);
//  - the contact solution (SMALSE-M + MPGP, tight tolerance) agrees: the
//    multipliers and the floating body's displacement (1e-8 relative);
//  - `assembled' with a solver without a Schur factor (UMFPACK) is a clear
//    error; `automatic' with a zero memory limit falls back to implicit and
//    says why.

#include <deal.II/base/function.h>

#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <fem/cholmod_solver.h>
#include <fem/umfpack_solver.h>

#include <test_tools.h>

#include "unit_box.h"

#include <iostream>
#include <random>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

template <int dim>
void
run(const unsigned int degree)
{
  std::cout << dim << "D, Q" << degree << std::endl;
  const double                        p = 1e6, tau = 1e5, g = 5e5;
  PressedBlocks<dim>                  blocks(2,
                            3,
                            degree,
                            p,
                            tau,
                            g,
                            [](const Point<dim> &center) {
                              return center[dim - 1] > 0.5 && center[0] < 0.5;
                            });
  auto                               &lower = blocks.lower;
  auto                               &upper = blocks.upper;
  contact::ContactDiscretization<dim> contact({lower.get(), upper.get()},
                                              {blocks.pair});
  const std::vector<const fem::ElasticBody<dim> *> bodies = {lower.get(),
                                                             upper.get()};
  const auto cholmod = [] { return std::make_unique<fem::CholmodSolver>(); };

  contact::DualProblemParameters assembled_parameters, implicit_parameters;
  assembled_parameters.form =
    contact::DualProblemParameters::Operator::assembled;
  implicit_parameters.form = contact::DualProblemParameters::Operator::implicit;
  contact::DualProblem<dim> assembled(bodies,
                                      contact,
                                      cholmod,
                                      assembled_parameters);
  contact::DualProblem<dim> implicit(bodies,
                                     contact,
                                     cholmod,
                                     implicit_parameters);
  check(assembled.is_assembled() && !implicit.is_assembled(),
        "forms: " + assembled.operator_description() + " / " +
          implicit.operator_description(),
        0);
  check(implicit.n_rigid_body_modes() == dim * (dim + 1) / 2,
        "rigid-body modes of the floating block",
        implicit.n_rigid_body_modes());

  // products with random vectors
  std::mt19937                           rng(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  const unsigned int                     m     = implicit.n_multipliers();
  double                                 worst = 0;
  for (unsigned int trial = 0; trial < 5; ++trial)
  {
    Vector<double> x(m), y1, y2;
    for (auto &v : x)
      v = uniform(rng);
    assembled.apply_F(y1, x);
    implicit.apply_F(y2, x);
    y1 -= y2;
    worst = std::max(worst, y1.l2_norm() / y2.l2_norm());
  }
  check(worst < 1e-10, "|F x assembled - F x implicit| / |F x|", worst);
  check(std::abs(assembled.scale() - implicit.scale()) <
          1e-8 * implicit.scale(),
        "lambda_max(F), relative difference",
        std::abs(assembled.scale() - implicit.scale()) / implicit.scale());
  check(implicit.n_stiffness_solves() > assembled.n_stiffness_solves(),
        "the assembled form spends no K^# solve on products",
        assembled.n_stiffness_solves());

  // the contact solutions
  qp::SolverParameters parameters;
  parameters.solver         = "mpgp";
  parameters.tolerance      = 1e-11;
  parameters.max_iterations = 100000;
  contact::ContactSolver<dim> solve_assembled(assembled, parameters, {}, {});
  contact::ContactSolver<dim> solve_implicit(implicit, parameters, {}, {});
  const auto                  r1 = solve_assembled.solve();
  const auto                  r2 = solve_implicit.solve();
  check(r1.converged && r2.converged,
        "both converged: " + r1.reason + " / " + r2.reason,
        0);
  Vector<double> dl = r1.lambda;
  dl -= r2.lambda;
  check(dl.l2_norm() < 1e-8 * r2.lambda.l2_norm(),
        "multipliers, relative difference",
        dl.l2_norm() / r2.lambda.l2_norm());
  Vector<double> du = r1.displacements[1];
  du -= r2.displacements[1];
  check(du.linfty_norm() < 1e-8 * r2.displacements[1].linfty_norm(),
        "floating block's displacement, relative difference",
        du.linfty_norm() / r2.displacements[1].linfty_norm());

  // errors and the fall-back
  bool thrown = false;
  try
  {
    contact::DualProblem<dim> umfpack(
      bodies,
      contact,
      [] { return std::make_unique<fem::UmfpackSolver>(); },
      assembled_parameters);
  }
  catch (const std::exception &e)
  {
    thrown = std::string(e.what()).find("set Operator = assembled") !=
             std::string::npos;
  }
  check(thrown, "assembled with UMFPACK: error naming the parameter", 0);
  contact::DualProblemParameters limited;
  limited.memory_limit = 0;
  contact::DualProblem<dim> fallback(bodies, contact, cholmod, limited);
  check(!fallback.is_assembled() && fallback.operator_description().find(
                                      "above the limit") != std::string::npos,
        "automatic with a zero memory limit: " +
          fallback.operator_description(),
        0);
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
