// SolverParameters in `subsection QP solver`, each solver's own in its
// subsection (MPGP-BB, MwPGP, PBBf, SPG-QP, APGD, Auto; the flat names of
// before are unknown entries): defaults are table 14's
// (alpha_bar factor 1.95, Gamma 1, PBBf/K 10, SPG-QP/m 10, gamma 0.1,
// sigma2 0.9999, alpha0 factor 1.95, APGD/L factor 1, 1e4 iterations);
// values read back from a .prm; out-of-range values rejected naming the
// parameter; every declared solver name either creates a solver or throws
// "unavailable"; power iteration on diag(1..n) finds n within its
// tolerance and applies the safety factor.  The registry: names in
// registration order are the pattern, the chains may hold every solver but
// auto (general sets: not mprgp), a solver registered by a program is
// created and chained by name and solves like the class it wraps (bitwise),
// a taken name is refused; make_solver picks the chain / SMALSE-M / the
// plain solver.
#include "planted_problems.h"

#include <deal.II/base/parameter_handler.h>

#include <qp/active_set_solver.h>
#include <qp/power_iteration.h>
#include <qp/problem_io.h>
#include <qp/solver_factory.h>
#include <qp/solver_registry.h>

#include <sstream>

using namespace qptest;
using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

int
main()
{
  Checker check;
  {
    dealii::ParameterHandler prm;
    SolverParameters::declare_parameters(prm);
    SolverParameters p;
    p.parse_parameters(prm);
    const SolverParameters d;
    // the one intended difference: the application's default solver is
    // the fall-back chain, the struct's a plain solver
    check.check(p.solver == "auto" && d.solver == "mprgp" &&
                  p.solver == SolverParameters::prm_default_solver &&
                  p.auto_chain.bounds == d.auto_chain.bounds &&
                  p.auto_chain.general == d.auto_chain.general &&
                  p.auto_chain.warm_start == d.auto_chain.warm_start &&
                  p.auto_chain.settings == d.auto_chain.settings,
                "the .prm default Solver is auto (the struct's mprgp), "
                "chains as the struct's");
    check.check(p.tolerance == 1e-8 && p.alpha_bar_factor == 1.95 &&
                  p.gamma == 1. && p.pbbf.k == 10 && p.spg.m == 10 &&
                  p.spg.gamma == 0.1 && p.spg.sigma2 == 0.9999 &&
                  p.spg.alpha0_factor == 1.95 && p.apgd.l_factor == 1. &&
                  p.mpgp_bb.memory == d.mpgp_bb.memory &&
                  p.power_tolerance == d.power_tolerance &&
                  p.power_max_iterations == d.power_max_iterations &&
                  p.stagnation_window == d.stagnation_window &&
                  p.projected_cg_gradient_factor ==
                    d.projected_cg_gradient_factor &&
                  p.max_iterations == 10000 &&
                  p.stopping_criterion == StoppingCriterion::projected &&
                  p.mwpgp.delta == d.mwpgp.delta &&
                  p.power_safety_factor == d.power_safety_factor,
                "defaults of the .prm equal the struct's (table 14)");
    prm.parse_input_from_string("subsection QP solver\n"
                                "  set Solver = mwpgp\n"
                                "  set Tolerance = 1e-6\n"
                                "  set Stopping criterion = reduced-projected\n"
                                "  set Maximum iterations = 77\n"
                                "  subsection MwPGP\n"
                                "    set Delta = 0.4\n"
                                "  end\n"
                                "  subsection SPG-QP\n"
                                "    set m = 7\n"
                                "  end\n"
                                "  subsection Auto\n"
                                "    set Warm start = false\n"
                                "  end\n"
                                "end\n");
    p.parse_parameters(prm);
    check.check(p.solver == "mwpgp" && p.tolerance == 1e-6 &&
                  p.stopping_criterion ==
                    StoppingCriterion::reduced_projected &&
                  p.max_iterations == 77 && p.mwpgp.delta == 0.4 &&
                  p.spg.m == 7 && !p.auto_chain.warm_start,
                "values read back from a .prm, own parameters from their "
                "subsections");
    bool rejected = false;
    try
    {
      prm.parse_input_from_string("subsection QP solver\n"
                                  "  subsection MwPGP\n"
                                  "    set Delta = 0.7\n"
                                  "  end\n"
                                  "end\n");
    }
    catch (const std::exception &)
    {
      rejected = true;
    }
    check.check(rejected, "MwPGP/Delta = 0.7 rejected by the pattern");
    // the flat names of before issue 16 are unknown entries now
    for (const std::string old : {"SPG-QP m",
                                  "MPGP-BB memory",
                                  "MwPGP delta",
                                  "PBBf K",
                                  "APGD L factor",
                                  "Auto chain for bounds",
                                  "Auto warm start",
                                  "Auto settings"})
    {
      std::string message;
      try
      {
        prm.parse_input_from_string("subsection QP solver\n  set " + old +
                                    " = 1\nend\n");
      }
      catch (const std::exception &e)
      {
        message = plain_message(e);
      }
      check.check(message.find(old) != std::string::npos,
                  "the flat name `" + old + "' is an unknown entry");
    }
    {
      std::string what_m;
      try
      {
        SolverParameters q;
        q.spg.m = 0;
        q.check();
      }
      catch (const std::exception &e)
      {
        what_m = plain_message(e);
      }
      check.check(what_m.find("QP solver/SPG-QP/m") != std::string::npos,
                  "check() names an own parameter by its path "
                  "(QP solver/SPG-QP/m)");
    }
    {
      // every own subsection is declared, through the registry
      std::ostringstream listing;
      prm.print_parameters(listing, dealii::ParameterHandler::PRM);
      bool all = true;
      for (const char *name :
           {"MPGP-BB", "MwPGP", "PBBf", "SPG-QP", "APGD", "Auto"})
        all = all && listing.str().find(std::string("subsection ") + name) !=
                       std::string::npos;
      check.check(all,
                  "subsections MPGP-BB, MwPGP, PBBf, SPG-QP, APGD, "
                  "Auto declared in QP solver");
    }
    std::string what;
    try
    {
      SolverParameters q;
      q.alpha_bar_factor = 2.5;
      q.check();
    }
    catch (const std::exception &e)
    {
      what = e.what();
    }
    check.check(what.find("Alpha bar factor") != std::string::npos &&
                  what.find("QP solver") != std::string::npos,
                "check() names the parameter and the subsection");
  }
  {
    std::istringstream names(solver_names());
    std::string        name;
    unsigned int       created = 0, total = 0;
    std::string        list;
    while (std::getline(names, name, '|'))
    {
      ++total;
      try
      {
        auto s = create<Vec>(name, SolverParameters());
        created += (s && s->name() == name) ? 1 : 0;
        list += " " + name;
      }
      catch (const std::exception &e)
      {
        check.check(std::string(e.what()).find(name) != std::string::npos,
                    "solver '" + name +
                      "' not available yet: message names it");
      }
    }
    check.check(created >= 4,
                "factory creates" + list + " (" + std::to_string(created) +
                  " of " + std::to_string(total) + " names)");
  }
  {
    SolverRegistry          &registry = SolverRegistry::instance();
    std::vector<std::string> names    = registry.names();
    std::string              joined;
    for (const std::string &name : names)
      joined += (joined.empty() ? "" : "|") + name;
    check.check(joined == solver_names() &&
                  joined ==
                    "mprgp|mpgp|mpgp-bb|mwpgp|spg-qp|pbbf|apgd|cgc|auto",
                "registry order is the Solver pattern: " + joined);
    const auto bounds  = registry.chainable_names(false);
    const auto general = registry.chainable_names(true);
    check.check(bounds.size() == 7 && bounds.front() == "mprgp" &&
                  general.size() == 6 && general.front() == "mpgp" &&
                  registry.find("auto") != nullptr &&
                  !registry.find("auto")->chainable &&
                  registry.find("cgc") != nullptr &&
                  !registry.find("cgc")->chainable,
                "chains hold 7 solvers (general sets 6: not mprgp), never "
                "auto or cgc");

    // a solver a program adds: found by create(), chains and the checks
    DUALCONTACT_QP_REGISTER_SOLVER(registry,
                                   MPGP,
                                   "test-mpgp",
                                   AcceptedSets::any_separable,
                                   "MPGP under another name");
    std::string refused;
    try
    {
      DUALCONTACT_QP_REGISTER_SOLVER(
        registry, MPGP, "test-mpgp", AcceptedSets::any_separable, "again");
    }
    catch (const std::exception &e)
    {
      refused = e.what();
    }
    check.check(refused.find("'test-mpgp' is registered twice") !=
                  std::string::npos,
                "a taken name is refused, naming it");
    const Planted P =
      make_planted({BlockType::bound, BlockType::disc}, 30, 8, 11);
    Vec              layout(P.x_star.size());
    auto             problem = make_problem(P.A, P.b, P.blocks, layout);
    SolverParameters prm;
    prm.tolerance = 1e-10;
    Vec        x(layout), y(layout);
    const auto a = create<Vec>("test-mpgp", prm)->solve(problem, x);
    const auto b = create<Vec>("mpgp", prm)->solve(problem, y);
    y -= x;
    check.check(a.converged() && a.iterations == b.iterations &&
                  y.linfty_norm() == 0.,
                "registered test-mpgp solves like mpgp: " +
                  std::to_string(a.iterations) + " iterations, same x");
    check.check(AutoChainParameters::parse_chain(
                  "test-mpgp, mprgp", false, "QP solver/Auto/Chain for bounds")
                    .size() == 2,
                "a chain may name the registered solver");
    std::string general_error;
    try
    {
      AutoChainParameters::parse_chain("mprgp",
                                       true,
                                       "QP solver/Auto/Chain for general "
                                       "sets");
    }
    catch (const std::exception &e)
    {
      general_error = plain_message(e);
    }
    check.check(general_error.find("mprgp takes bound and box constraints "
                                   "only") != std::string::npos &&
                  general_error.find("test-mpgp") != std::string::npos,
                "mprgp in a general chain refused, listing the solvers "
                "that may stand there");

    // make_solver: the chain, SMALSE-M around the solver, the solver
    SolverParameters named;
    named.solver = "mpgp";
    SolverParameters chain;
    chain.solver = "auto";
    check.check(
      make_solver<Vec>(chain, SMALSEMParameters(), true)->name() == "auto" &&
        make_solver<Vec>(named, SMALSEMParameters(), true)->name() ==
          "smalse-m(mpgp)" &&
        make_solver<Vec>(named, SMALSEMParameters(), problem)->name() == "mpgp",
      "make_solver: auto -> the chain, with equality -> "
      "smalse-m(mpgp), without -> mpgp");
  }
  {
    const unsigned                                n = 50;
    Vec                                           layout(n);
    const std::function<void(Vec &, const Vec &)> A =
      [](Vec &dst, const Vec &src)
    {
      for (unsigned i = 0; i < src.size(); ++i)
        dst[i] = (i + 1.) * src[i];
    };
    const auto r = power_iteration<Vec>(A, layout, 2000, 1e-10, 1.05);
    check.check(std::abs(r.estimate - n) <= 1e-3 * n &&
                  std::abs(r.lambda_max - 1.05 * r.estimate) <= 1e-12 * n,
                "power iteration on diag(1..50): estimate " + sci(r.estimate) +
                  " after " + std::to_string(r.iterations) +
                  " products, lambda_max " + sci(r.lambda_max));
    const auto r2 = power_iteration<Vec>(A, layout, 100, 1e-4, 1.05);
    check.check(r2.estimate <= n * (1. + 1e-12) && r2.estimate >= 0.9 * n,
                "power iteration, default budget: estimate " +
                  sci(r2.estimate) + " (from below) in " +
                  std::to_string(r2.iterations) + " products");
    // Lanczos: from below, and far closer than the power iteration with
    // the same tolerance and fewer products
    const auto l = lanczos_lambda_max<Vec>(A, layout, 100, 1e-4, 1.05);
    check.check(l.estimate <= n * (1. + 1e-12) &&
                  std::abs(l.estimate - n) <= 1e-3 * n &&
                  std::abs(l.lambda_max - 1.05 * l.estimate) <= 1e-12 * n &&
                  l.n_products < r2.n_products,
                "Lanczos on diag(1..50): estimate " + sci(l.estimate) + " in " +
                  std::to_string(l.n_products) +
                  " products (power iteration: " + sci(r2.estimate) + " in " +
                  std::to_string(r2.n_products) + ")");
    // a rank-one A = u u' (invariant subspace after one step): exact
    const std::function<void(Vec &, const Vec &)> R =
      [](Vec &dst, const Vec &src)
    {
      double s = 0;
      for (unsigned i = 0; i < src.size(); ++i)
        s += src[i];
      for (unsigned i = 0; i < src.size(); ++i)
        dst[i] = s;
    };
    const auto one = lanczos_lambda_max<Vec>(R, layout, 100, 1e-4, 1.);
    check.check(std::abs(one.estimate - n) <= 1e-12 * n && one.n_products <= 2,
                "Lanczos on the rank-one ones(50): estimate " +
                  sci(one.estimate) + " in " + std::to_string(one.n_products) +
                  " products");
  }
  return check.finish("parameters");
}
