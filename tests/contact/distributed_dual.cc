// The dual QP on distributed vectors (dealii::TrilinosWrappers::MPI::Vector,
// `set QP vectors = distributed') against the replicated one
// (dealii::Vector<double> on every process), run on 1 and 2 processes
// (tests/contact/distributed_dual.mpirun).  Scene: a clamped lower block
// with a locally refined top and a floating upper block pressed and sheared
// onto it (PressedBlocks: SMALSE-M with G = R'B', non-matching meshes),
// Tresca and Coulomb friction, 3D (disc sets).  The
// bodies are on plain triangulations, so the contact nodes are split evenly
// over the processes; every process factorizes K itself (CHOLMOD), which
// lets both forms of F run distributed.  Checked:
//  - every process owns whole contact nodes: normal and tangential
//    multipliers of a node together; on 2 processes both own some, and the
//    owned counts add up to the multipliers;
//  - F x (implicit and assembled, distributed) = F x (replicated) for
//    random x, 1e-12 relative;
//  - Tresca (both forms): the same multipliers (1e-8 relative) and
//  floating-block
//    displacements (1e-8 relative), the QP ran on the Trilinos vector type,
//    with the same global block count in its separable set;
//  - Coulomb (mu = 0.3, assembled F): the fixed point gives the same
//    multipliers (1e-8) in the same number of Tresca solves.

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>

#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <fem/cholmod_solver.h>

#include "unit_box.h"

#include <iostream>
#include <random>

using namespace dealii;
using namespace dualcontact;

namespace
{
  int failures = 0;

  /** A check that holds on every process; printed by process 0. */
  void
  check(const bool ok, const std::string &what, const double value)
  {
    const bool all = Utilities::MPI::min(ok ? 1 : 0, MPI_COMM_WORLD) == 1;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::cout << (all ? "  ok   " : "  FAIL ") << what << ": " << value
                << std::endl;
    if (!all)
      ++failures;
  }

  double
  relative_difference(const Vector<double> &a, const Vector<double> &b)
  {
    Vector<double> d = a;
    d -= b;
    return d.l2_norm() / std::max(b.l2_norm(), 1e-300);
  }
} // namespace


template <int dim>
void
run()
{
  const unsigned int n_processes =
    Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << dim << "D, " << n_processes << " process(es)" << std::endl;
  const double                                     p = 1e6, tau = 1e5, g = 5e5;
  PressedBlocks<dim>                               blocks(2,
                            3,
                            1,
                            p,
                            tau,
                            g,
                            [](const Point<dim> &center) {
                              return center[dim - 1] > 0.5 && center[0] < 0.5;
                            });
  const std::vector<const fem::ElasticBody<dim> *> bodies = {
    blocks.lower.get(), blocks.upper.get()};
  const auto cholmod = [] { return std::make_unique<fem::CholmodSolver>(); };

  for (const bool coulomb : {false, true})
  {
    auto pair = blocks.pair;
    if (coulomb)
    {
      pair.friction.type  = contact::FrictionLaw::Type::coulomb_isotropic;
      pair.friction.first = 0.3;
    }
    contact::ContactDiscretization<dim> discretization(bodies, {pair});
    const std::string                   law = coulomb ? "Coulomb" : "Tresca";

    contact::DualProblemParameters replicated_parameters, implicit_parameters,
      assembled_parameters;
    replicated_parameters.vectors =
      contact::DualProblemParameters::Vectors::replicated;
    replicated_parameters.form =
      contact::DualProblemParameters::Operator::implicit;
    implicit_parameters.vectors =
      contact::DualProblemParameters::Vectors::distributed;
    implicit_parameters.form =
      contact::DualProblemParameters::Operator::implicit;
    assembled_parameters.vectors =
      contact::DualProblemParameters::Vectors::distributed;
    assembled_parameters.form =
      contact::DualProblemParameters::Operator::assembled;
    contact::DualProblem<dim> replicated(bodies,
                                         discretization,
                                         cholmod,
                                         replicated_parameters);
    contact::DualProblem<dim> implicit(bodies,
                                       discretization,
                                       cholmod,
                                       implicit_parameters);
    contact::DualProblem<dim> assembled(bodies,
                                        discretization,
                                        cholmod,
                                        assembled_parameters);
    const unsigned int        m = replicated.n_multipliers();
    check(!replicated.is_distributed() && implicit.is_distributed() &&
            assembled.is_distributed() && assembled.is_assembled() &&
            !implicit.is_assembled(),
          law + ": forms and vectors as asked",
          m);

    // whole nodes per process
    const IndexSet    &owned   = implicit.locally_owned_multipliers();
    const unsigned int n_nodes = implicit.n_contact_nodes();
    bool               whole   = true;
    for (unsigned int i = 0; i < n_nodes; ++i)
    {
      const int j = implicit.frictional_index(i);
      if (j >= 0)
        for (unsigned int k = 0; k + 1 < dim; ++k)
          whole = whole && owned.is_element(n_nodes + (dim - 1) * j + k) ==
                             owned.is_element(i);
    }
    check(whole,
          law + ": a node's normal and tangential multipliers on one process",
          owned.n_elements());
    const auto  &counts  = implicit.multipliers_per_process();
    unsigned int total   = 0;
    bool         all_own = counts.size() == n_processes;
    for (const unsigned int c : counts)
    {
      total += c;
      all_own = all_own && c > 0;
    }
    check(total == m && all_own,
          law + ": every process owns multipliers, together all of them",
          total);

    // products
    std::mt19937                           rng(11);
    std::uniform_real_distribution<double> uniform(-1, 1);
    double                                 worst = 0;
    for (unsigned int trial = 0; trial < 3; ++trial)
    {
      Vector<double> x(m), y, z;
      for (auto &v : x)
        v = uniform(rng);
      replicated.apply_F(y, x);
      for (const contact::DualProblem<dim> *dual : {&implicit, &assembled})
      {
        TrilinosWrappers::MPI::Vector xd, yd;
        dual->initialize_multipliers(xd);
        unsigned int k = 0;
        for (const auto r : dual->locally_owned_multipliers())
          xd.begin()[k++] = x(r);
        dual->apply_F(yd, xd);
        dual->gather(yd, z);
        worst = std::max(worst, relative_difference(z, y));
      }
    }
    check(worst < 1e-12,
          law + ": |F x distributed - F x replicated| / |F x| (implicit, "
                "assembled)",
          worst);
    {
      const auto serial_set = replicated.make_problem().constraints->n_blocks();
      const auto distributed_set =
        implicit.make_distributed_problem().constraints->n_blocks();
      check(serial_set == distributed_set,
            law + ": global number of blocks of the separable set",
            distributed_set);
    }

    // the contact solutions
    qp::SolverParameters parameters;
    parameters.solver         = "mpgp";
    parameters.tolerance      = 1e-11;
    parameters.max_iterations = 100000;
    contact::CoulombParameters coulomb_parameters;
    const auto reference = contact::ContactSolver<dim>(replicated,
                                                       parameters,
                                                       {},
                                                       coulomb_parameters)
                             .solve();
    // Coulomb: the assembled form only (its QPs take some 27000 iterations
    // here; with a K^# solve per product that is too slow for a test)
    std::vector<contact::DualProblem<dim> *> forms = {&assembled};
    if (!coulomb)
      forms.insert(forms.begin(), &implicit);
    for (contact::DualProblem<dim> *dual : forms)
    {
      const std::string form = dual == &implicit ? "implicit" : "assembled";
      const auto        r =
        contact::ContactSolver<dim>(*dual, parameters, {}, coulomb_parameters)
          .solve();
      unsigned int iterations = 0;
      double       seconds    = 0;
      for (const auto &q : r.qp_statistics)
      {
        iterations += q.iterations;
        seconds += q.wall_time;
      }
      check(reference.converged && r.converged,
            law + ", " + form + ": both converged (" + reference.reason +
              " / " + r.reason + "; " + std::to_string(iterations) +
              " QP iterations, " + std::to_string(seconds) +
              " s in the QPs), QP solves",
            r.qp_statistics.size());
      check(r.qp_vectors == "dealii::TrilinosWrappers::MPI::Vector" &&
              reference.qp_vectors == "dealii::Vector<double>" &&
              r.multipliers_per_process == counts,
            law + ", " + form + ": the QP ran on " + r.qp_vectors +
              ", multipliers on this process",
            owned.n_elements());
      check(r.qp_statistics.size() == reference.qp_statistics.size(),
            law + ", " + form + ": as many QP solves as replicated",
            reference.qp_statistics.size());
      const double dl = relative_difference(r.lambda, reference.lambda);
      check(dl < 1e-8, law + ", " + form + ": multipliers, relative", dl);
      const double du =
        relative_difference(r.displacements[1], reference.displacements[1]);
      check(du < 1e-8,
            law + ", " + form + ": floating block's displacement, relative",
            du);
      // the recovery from the gathered multipliers (the output's path)
      std::vector<Vector<double>> again;
      dual->recover(r.lambda, again);
      const double dr = relative_difference(again[1], r.displacements[1]);
      check(dr < 1e-12,
            law + ", " + form + ": recovery from the gathered multipliers",
            dr);
    }
  }
}


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  try
  {
    // 3D only (disc sets); the 2D box sets run distributed in
    // tests/mpi/floating_blocks_ranks
    run<3>();
  }
  catch (const std::exception &e)
  {
    std::cerr << "exception: " << e.what() << std::endl;
    return 1;
  }
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << (failures == 0 ? "all checks passed" : "FAILED") << std::endl;
  return failures == 0 ? 0 : 1;
}
