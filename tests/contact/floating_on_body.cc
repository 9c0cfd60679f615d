// A floating body pressed onto another body: the upper block has no
// Dirichlet condition at all (dim (dim + 1) / 2 rigid-body modes), the lower
// block is clamped at its base; non-matching meshes, Tresca friction between
// them with a slip bound above the shear that arises.  The upper block
// carries a pressure p on its top (and, for a non-trivial tangential
// balance, a shear tau < slip bound).  Checked, 2D and 3D: the QP (SMALSE-M)
// converges; the contact forces balance the loads of the floating body
// (normal p |A|, tangential tau |A|) to 1e-8; the gaps stay closed where the
// normal multiplier is positive (|B_N u - c| small) and no node penetrates;
// the floating body's displacement is the same for two different dual
// solvers, MPGP and SPG-QP (1e-6).

#include <deal.II/base/function.h>
#include <deal.II/grid/grid_generator.h>

#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <fem/cholmod_solver.h>

#include <test_tools.h>

#include "unit_box.h"

#include <iostream>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

template <int dim>
void
run()
{
  std::cout << dim << "D" << std::endl;
  const double                        p = 1e6, tau = 1e5, g = 5e5;
  PressedBlocks<dim>                  blocks(3, 4, 1, p, tau, g);
  auto                               &lower = blocks.lower;
  auto                               &upper = blocks.upper;
  contact::ContactDiscretization<dim> contact({lower.get(), upper.get()},
                                              {blocks.pair});
  contact::DualProblem<dim>           dual(
    {lower.get(), upper.get()},
    contact,
    [] { return std::make_unique<fem::CholmodSolver>(); });
  check(dual.n_rigid_body_modes() == dim * (dim + 1) / 2,
        "rigid-body modes",
        dual.n_rigid_body_modes());

  Vector<double> first;
  for (const std::string solver : {"mpgp", "spg-qp"})
  {
    qp::SolverParameters parameters;
    parameters.solver         = solver;
    parameters.tolerance      = 1e-10;
    parameters.max_iterations = 100000;
    contact::ContactSolver<dim> contact_solver(dual, parameters, {}, {});
    const auto                  result = contact_solver.solve();
    const unsigned int          n      = contact.n_nodes();
    Tensor<1, dim>              force; // on the upper body from the contact
    for (unsigned int i = 0; i < n; ++i)
    {
      const auto &node = contact.nodes()[i];
      force -= result.lambda(i) * node.normal;
      for (unsigned int k = 0; k + 1 < dim; ++k)
        force -= result.lambda(n + (dim - 1) * i + k) * node.tangents[k];
    }
    Tensor<1, dim> applied = upper->applied_force();
    const double   balance = (force + applied).norm() / p;
    check(result.converged && balance < 1e-8,
          solver + ": " + result.reason + ", |contact + applied| / p",
          balance);

    // complementarity in the primal: gaps closed where pressed, none negative
    Vector<double> u(contact.n_dofs());
    for (unsigned int b = 0; b < 2; ++b)
      for (unsigned int i = 0; i < result.displacements[b].size(); ++i)
        u(contact.body_offset(b) + i) = result.displacements[b](i);
    Vector<double> bn(n);
    contact.normal_matrix().vmult(bn, u);
    const Vector<double> c = contact.normal_bound();
    double scale = u.linfty_norm(), penetration = 0, open_pressed = 0;
    for (unsigned int i = 0; i < n; ++i)
    {
      penetration = std::max(penetration, (bn(i) - c(i)) / scale);
      if (result.lambda(i) > 1e-6 * p * contact.nodes()[i].weight)
        open_pressed = std::max(open_pressed, std::abs(bn(i) - c(i)) / scale);
    }
    check(penetration < 1e-6,
          solver + ": max penetration / max|u|",
          penetration);
    check(open_pressed < 1e-6,
          solver + ": max gap at pressed nodes / max|u|",
          open_pressed);
    if (first.size() == 0)
      first = result.displacements[1];
    Vector<double> diff = result.displacements[1];
    diff -= first;
    check(diff.linfty_norm() < 1e-6 * first.linfty_norm(),
          solver + ": floating body's displacement vs mpgp",
          diff.linfty_norm() / first.linfty_norm());
  }
}

int
main()
{
  try
  {
    run<2>();
    run<3>();
  }
  catch (const std::exception &e)
  {
    std::cerr << "exception: " << e.what() << std::endl;
    return 1;
  }
  return test_tools::finish();
}
