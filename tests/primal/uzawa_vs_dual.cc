// The primal Uzawa-CGC method (lib/primal) against the dual solvers
// (lib/contact + lib/qp) on small 2D plane-strain scenes: both solve the
// same discrete problem, so at tight tolerances the displacements agree to
// 1e-6 (relative, max norm) and the contact forces to 1e-5, for every
// preconditioner and version:
//  A. a block on a rigid plane, its top face moved down and sideways
//     (prescribed displacement), Tresca friction: part of the contact
//     sticks, part slips (asserted, so that the friction is not trivial);
//  B. a block pressed onto a clamped block (non-matching meshes,
//     node-to-segment rows coupling both bodies), Tresca;
//  C. scene A with Coulomb friction (fixed point over Tresca problems).
// The dual QP by CGC (the report's DUAL, `Solver = cgc') agrees with MPGP
// to 1e-8 / 1e-7.  Also: the CGC outer iterations of the first solve start on
// the facet of all contact constraints (the report's tables 11.3-11.10), and
// the multipliers respect |lambda_T| <= psi.

#include <deal.II/base/function.h>

#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <fem/cholmod_solver.h>
#include <primal/block_scenes.h>
#include <primal/uzawa_cgc.h>

#include <test_tools.h>

#include <iostream>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

using namespace block_scenes;

void
compare(const std::string &name, Scene &scene, const bool expect_partial_slip)
{
  contact::DualProblem<2> dual(scene.pointers,
                               *scene.contact,
                               [] {
                                 return std::make_unique<fem::CholmodSolver>();
                               });
  qp::SolverParameters    qp_parameters;
  qp_parameters.solver         = "mpgp";
  qp_parameters.tolerance      = 1e-12;
  qp_parameters.max_iterations = 200000;
  contact::CoulombParameters coulomb;
  coulomb.tolerance      = 1e-9;
  coulomb.max_iterations = 100;
  contact::ContactSolver<2> dual_solver(dual, qp_parameters, {}, coulomb);
  const auto                reference = dual_solver.solve();
  check(reference.converged,
        name + ": dual solver converged",
        reference.reason);
  const unsigned int n = scene.contact->n_nodes();

  // the report's DUAL method: the same dual QP by CGC
  {
    qp::SolverParameters cgc_parameters = qp_parameters;
    cgc_parameters.solver               = "cgc";
    contact::ContactSolver<2> cgc_solver(dual, cgc_parameters, {}, coulomb);
    const auto                by_cgc = cgc_solver.solve();
    check(by_cgc.converged, name + ": dual by CGC converged", by_cgc.reason);
    const double du =
      relative_difference(by_cgc.displacements, reference.displacements);
    check(du < 1e-8, name + ": dual by CGC vs MPGP, displacements", du);
    const double rl = relative_difference(by_cgc.lambda, reference.lambda);
    check(rl < 1e-7, name + ": dual by CGC vs MPGP, multipliers", rl);
  }

  for (const auto &[preconditioner, version] :
       std::vector<std::pair<std::string, std::string>>{{"none", "pcg2"},
                                                        {"diagonal", "pcg2"},
                                                        {"ssor", "pcg2"},
                                                        {"ic", "pcg2"},
                                                        {"icd", "pcg1"},
                                                        {"cholesky", "pcg1"},
                                                        {"cholesky", "pcg2"}})
  {
    primal::PrimalParameters parameters;
    parameters.preconditioner    = preconditioner;
    parameters.version           = version;
    parameters.omega             = 1.2;
    parameters.cgc_tolerance     = 1e-12;
    parameters.uzawa_tolerance   = 1e-10;
    parameters.uzawa_step_factor = 1.5;
    primal::UzawaCGC<2> primal(scene.pointers,
                               *scene.contact,
                               parameters,
                               coulomb);
    const auto          result = primal.solve();
    const std::string   label =
      name + " " + preconditioner + "/" + version + ": ";
    check(result.converged,
          label + result.reason + ", Uzawa iterations " +
            std::to_string(result.uzawa_iterations) + ", Tresca problems " +
            std::to_string(result.n_tresca) + ", CG steps",
          result.total_inner_iterations);
    const double du =
      relative_difference(result.displacements, reference.displacements);
    check(du < 1e-6, label + "displacement vs dual, relative difference", du);
    const double rl = relative_difference(result.lambda, reference.lambda);
    check(rl < 1e-5, label + "multipliers vs dual, relative difference", rl);
    check(!result.first_outer.empty() && result.first_outer[0].n_active == n,
          label + "first CGC outer iteration on the facet of all " +
            std::to_string(n) + " constraints, outer iterations",
          result.first_outer.size());
  }

  // friction state of the dual answer: psi from the dual problem
  unsigned int n_stick = 0, n_slip = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    const double u = dual.friction_utilization(reference.lambda, i);
    if (reference.lambda(i) <= 0.)
      continue;
    if (u < 1. - 1e-6)
      ++n_stick;
    else
      ++n_slip;
    check(u <= 1. + 1e-8,
          name + ": |lambda_T| <= psi at node " + std::to_string(i),
          u);
  }
  if (expect_partial_slip)
    check(n_stick > 0 && n_slip > 0,
          name + ": nodes in contact stick and slip, sticking",
          n_stick);
}

int
main()
{
  {
    auto scene = block_on_plane(
      friction_law(contact::FrictionLaw::Type::tresca_isotropic, 1.5e5));
    compare("A (block on plane, Tresca)", scene, true);
  }
  {
    auto scene = two_blocks(
      friction_law(contact::FrictionLaw::Type::tresca_isotropic, 5e4));
    compare("B (two blocks, Tresca)", scene, true);
  }
  {
    auto scene = block_on_plane(
      friction_law(contact::FrictionLaw::Type::coulomb_isotropic, 0.1));
    compare("C (block on plane, Coulomb)", scene, false);
  }
  return test_tools::finish();
}
