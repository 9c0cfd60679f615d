// The settings `Solver = auto' gives its solvers (SolverChain::
// attempt_parameters, `Auto/Settings', issue 20):
//  1. the choice per problem kind, on one bound problem: an assembled
//     sparse Hessian with an AMG factory -> MPRGP with Gamma 2, projected-CG
//     expansion (8 trials, gradient factor 1.25), AMG in face and the
//     preconditioned release; sparse without a factory -> Gamma 2 and
//     projected-CG only; dense (the contact dual, FCLIB) and operator-only
//     Hessians, equality constraints, the fall-back solvers, `Auto/Settings
//     = given' and a Gamma the user set -> the parameters given, unchanged;
//     MPGP-BB and MPGP on ellipses beside unconstrained unknowns (TFETI's
//     gluing multipliers), with equality constraints and an operator-only
//     Hessian -> projected-CG (MPGP-BB also Gamma 2), the same ellipses
//     without free unknowns -> the parameters given; and MPGP-BB with
//     those settings solves that problem to its planted solution;
//  2. the membrane of benchmark B4 (PERMON's variant, h = 100, n = 10,100,
//     ||g^P|| <= 1e-6 ||b||) with the default parameters: the chain runs
//     one attempt, mprgp with those settings, converged in at most 20
//     iterations (measured 13), and its record says so ("measured: ...
//     preconditioner=amg"); with `Auto/Settings = given' (the thesis'
//     table 14) the same chain needs more than ten times as many (measured
//     932): bounds that fail if the measured settings are not applied.
#include "planted_problems.h"

#include <qp/free_set_amg.h>
#include <qp/membrane_generator.h>
#include <qp/solver_chain.h>
#include <qp/solver_factory.h>

#include <deal.II/base/mpi.h>

using namespace qptest;
using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

namespace
{
  bool
  thesis_settings(const SolverParameters &p)
  {
    const SolverParameters thesis;
    return p.gamma == thesis.gamma && p.expansion == thesis.expansion &&
           p.projected_cg_trials == thesis.projected_cg_trials &&
           p.projected_cg_gradient_factor ==
             thesis.projected_cg_gradient_factor &&
           p.preconditioner == thesis.preconditioner &&
           p.proportioning_step == thesis.proportioning_step;
  }

  bool
  contains(const std::string &text, const std::string &piece)
  {
    return text.find(piece) != std::string::npos;
  }
} // namespace

int
main(int argc, char **argv)
{
  // Trilinos' AMG needs MPI
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checker                                  check;

  MembraneGenerator::Parameters mprm;
  mprm.variant                = MembraneGenerator::Variant::permon;
  mprm.h                      = 100;
  mprm.load_scale             = 1.;
  const auto         membrane = MembraneGenerator(mprm).generate();
  const unsigned int n        = membrane->size();
  FreeSetAMG         amg(membrane->hessian);

  const auto make = [&](const HessianStorage storage, const bool factory)
  {
    Problem<Vec> problem;
    problem.hessian = [&membrane](Vec &dst, const Vec &src)
    { membrane->hessian.vmult(dst, src); };
    problem.b = membrane->rhs;
    auto set  = std::make_shared<SeparableSet<Vec>>();
    for (unsigned int i = 0; i < n; ++i)
      set->add_bound(i, membrane->constraints[0].lower[i]);
    set->finalize(problem.b);
    problem.constraints     = set;
    problem.hessian_storage = storage;
    if (factory)
      problem.free_set_preconditioner = amg.factory();
    return problem;
  };

  // ---- 1. the choice per problem kind
  {
    SolverParameters prm;
    prm.tolerance = 1e-6;
    const SolverChain<Vec> chain(prm);
    const auto             sparse = make(HessianStorage::sparse_matrix, true);
    const auto             p      = chain.attempt_parameters(sparse, "mprgp");
    check.check(p.solver == "mprgp" && p.gamma == 2. &&
                  p.expansion == "projected-cg" && p.projected_cg_trials == 8 &&
                  p.projected_cg_gradient_factor == 1.25 &&
                  p.preconditioner == "amg" &&
                  p.proportioning_step == "preconditioned" &&
                  p.auto_chain.settings == "measured",
                "sparse Hessian with an AMG factory: mprgp with Gamma 2, "
                "projected-CG T8 R1.25, amg, preconditioned release (" +
                  SolverChain<Vec>::describe_settings(p) + ")");
    const auto no_factory =
      chain.attempt_parameters(make(HessianStorage::sparse_matrix, false),
                               "mprgp");
    check.check(no_factory.gamma == 2. &&
                  no_factory.expansion == "projected-cg" &&
                  no_factory.projected_cg_trials == 1 &&
                  no_factory.preconditioner == "none" &&
                  no_factory.proportioning_step == "chopped-gradient",
                "sparse Hessian without a factory: Gamma 2 and projected-CG "
                "only (" +
                  SolverChain<Vec>::describe_settings(no_factory) + ")");
    for (const auto &[storage, label] :
         std::vector<std::pair<HessianStorage, std::string>>{
           {HessianStorage::dense_matrix, "dense"},
           {HessianStorage::operator_only, "operator"}})
    {
      const auto q = chain.attempt_parameters(make(storage, true), "mprgp");
      check.check(thesis_settings(q) && q.solver == "mprgp",
                  label + " Hessian: the parameters given (thesis' table 14)");
    }
    const auto fall_back = chain.attempt_parameters(sparse, "mpgp-bb");
    check.check(thesis_settings(fall_back) && fall_back.solver == "mpgp-bb",
                "the fall-back mpgp-bb: the parameters given");
    auto with_equality     = make(HessianStorage::sparse_matrix, true);
    with_equality.equality = std::make_shared<EqualityConstraints<Vec>>();
    check.check(thesis_settings(
                  chain.attempt_parameters(with_equality, "mprgp")),
                "equality constraints (SMALSE-M): the parameters given");

    // ellipses beside free unknowns (TFETI's dual) and without them
    for (const unsigned int n_free : {12u, 0u})
    {
      const Planted P =
        make_planted({BlockType::ellipse, BlockType::bound}, 20, n_free, 11);
      Vec  layout(P.x_star.size());
      auto tfeti_like            = make_problem(P.A, P.b, P.blocks, layout);
      tfeti_like.equality        = std::make_shared<EqualityConstraints<Vec>>();
      tfeti_like.hessian_storage = HessianStorage::operator_only;
      const auto        bb    = chain.attempt_parameters(tfeti_like, "mpgp-bb");
      const auto        pg    = chain.attempt_parameters(tfeti_like, "mpgp");
      const std::string label = std::to_string(n_free) + " free unknowns: ";
      if (n_free > 0)
      {
        check.check(bb.gamma == 2. && bb.expansion == "projected-cg" &&
                      bb.projected_cg_trials == 1 &&
                      bb.preconditioner == "none" &&
                      bb.auto_chain.settings == "measured" &&
                      contains(SolverChain<Vec>::describe_settings(bb),
                               "expansion=projected-cg"),
                    label + "mpgp-bb with Gamma 2 and projected-CG (" +
                      SolverChain<Vec>::describe_settings(bb) + ")");
        check.check(pg.gamma == 1. && pg.expansion == "projected-cg",
                    label + "mpgp with projected-CG (" +
                      SolverChain<Vec>::describe_settings(pg) + ")");
        // MPGP-BB with these settings reaches the planted solution
        SolverParameters run = bb;
        run.tolerance        = 1e-10;
        Vec        x(P.x_star.size());
        auto       plain = make_problem(P.A, P.b, P.blocks, layout);
        const auto s     = create<Vec>("mpgp-bb", run)->solve(plain, x);
        check.check(s.converged() &&
                      distance(x, P.x_star) <= 1e-8 * (1. + norm(P.x_star)),
                    label + "mpgp-bb with them: " + to_string(s.reason) +
                      " in " + std::to_string(s.iterations) +
                      " iterations, |x - x*| = " + sci(distance(x, P.x_star)));
      }
      else
        check.check(thesis_settings(bb) && thesis_settings(pg),
                    label + "the parameters given");
    }

    SolverParameters given    = prm;
    given.auto_chain.settings = "given";
    check.check(thesis_settings(
                  SolverChain<Vec>(given).attempt_parameters(sparse, "mprgp")),
                "Auto/Settings = given: the parameters given");
    SolverParameters user = prm;
    user.gamma            = 3.;
    const auto u = SolverChain<Vec>(user).attempt_parameters(sparse, "mprgp");
    check.check(u.gamma == 3. && u.expansion == "alpha-bar" &&
                  u.preconditioner == "none" &&
                  u.auto_chain.settings == "given",
                "Gamma = 3 set by the user: kept, nothing measured added (" +
                  SolverChain<Vec>::describe_settings(u) + ")");
  }

  // ---- 2. the membrane with the defaults, and with the thesis' settings
  unsigned int measured_iterations = 0;
  {
    SolverParameters prm;
    prm.tolerance      = 1e-6;
    prm.max_iterations = 100000;
    SolverChain<Vec> chain(prm);
    const auto       problem = make(HessianStorage::sparse_matrix, true);
    Vec              x(n);
    const auto       s  = chain.solve(problem, x);
    measured_iterations = s.iterations;
    std::cout << "membrane (permon) h = 100, defaults: " << s.iterations
              << " iterations, " << s.n_hessian_products << " products, "
              << s.n_preconditioner_setups << " AMG setups; " << s.settings
              << std::endl;
    check.check(s.converged() && s.attempts.size() == 1 &&
                  s.attempts[0].solver == "mprgp" && s.iterations <= 20 &&
                  s.kkt.stationarity <= 1e-6 * s.norm_b &&
                  s.kkt.feasibility <= 1e-12 &&
                  s.n_preconditioner_setups >= 1 &&
                  s.n_preconditioned_releases >= 1 &&
                  contains(s.settings, "measured: gamma=2") &&
                  contains(s.settings, "preconditioner=amg") &&
                  contains(s.settings, "proportioning=preconditioned") &&
                  chain.chosen_parameters().preconditioner == "amg",
                "membrane h = 100, auto with defaults: one attempt, mprgp "
                "with the AMG in face, converged in " +
                  std::to_string(s.iterations) + " <= 20 iterations");
  }
  {
    SolverParameters prm;
    prm.tolerance           = 1e-6;
    prm.max_iterations      = 100000;
    prm.auto_chain.settings = "given";
    SolverChain<Vec> chain(prm);
    Vec              x(n);
    const auto s = chain.solve(make(HessianStorage::sparse_matrix, true), x);
    std::cout << "membrane (permon) h = 100, Auto/Settings = given: "
              << s.iterations << " iterations; " << s.settings << std::endl;
    check.check(s.converged() && s.n_preconditioner_setups == 0 &&
                  contains(s.settings, "given: gamma=1") &&
                  s.iterations > 10 * measured_iterations,
                "membrane h = 100, Auto/Settings = given: thesis MPRGP, " +
                  std::to_string(s.iterations) + " iterations > 10 x " +
                  std::to_string(measured_iterations));
  }
  return check.finish("qp/auto_settings");
}
