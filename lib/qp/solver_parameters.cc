#include <qp/solver_factory.h>
#include <qp/solver_parameters.h>
#include <qp/solver_registry.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

namespace dualcontact
{
  namespace qp
  {
    std::string
    to_string(const StoppingCriterion criterion)
    {
      switch (criterion)
      {
        case StoppingCriterion::projected:
          return "projected";
        case StoppingCriterion::reduced:
          return "reduced";
        case StoppingCriterion::reduced_projected:
          return "reduced_projected";
      }
      Assert(false, dealii::ExcInternalError());
      return "";
    }


    StoppingCriterion
    parse_stopping_criterion(const std::string &name)
    {
      if (name == "projected")
        return StoppingCriterion::projected;
      if (name == "reduced")
        return StoppingCriterion::reduced;
      if (name == "reduced_projected" || name == "reduced-projected")
        return StoppingCriterion::reduced_projected;
      AssertThrow(false,
                  dealii::ExcMessage(
                    "Unknown stopping criterion '" + name +
                    "': expected projected, reduced or reduced-projected."));
      return StoppingCriterion::projected;
    }


    void
    SolverParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Bool;
      using dealii::Patterns::Double;
      using dealii::Patterns::Integer;
      using dealii::Patterns::Selection;
      const SolverParameters d;

      prm.enter_subsection("QP solver");
      // the application's default is the fall-back chain; the library's
      // (SolverParameters::solver, used by code that builds the struct
      // itself) stays mprgp
      prm.declare_entry("Solver",
                        "auto",
                        Selection(solver_names()),
                        "Algorithm for the QP with separable constraints "
                        "(thesis chapter 2; SMALSE-M around it when the "
                        "problem has equality constraints). " +
                          SolverRegistry::instance().descriptions() +
                          ". Unit: none.");
      prm.declare_entry("Auto chain for bounds",
                        d.auto_chain_bounds,
                        dealii::Patterns::Anything(),
                        "Solver auto, every block a bound or box: the "
                        "solvers tried in this order, comma-separated; the "
                        "next runs only when the previous did not converge "
                        "(any reason). Unit: none.");
      prm.declare_entry("Auto chain for general sets",
                        d.auto_chain_general,
                        dealii::Patterns::Anything(),
                        "Solver auto, some block a disc, ellipse or cone: "
                        "the solvers tried in this order (not mprgp, which "
                        "takes bounds and boxes only). Unit: none.");
      prm.declare_entry("Auto warm start",
                        d.auto_warm_start ? "true" : "false",
                        Bool(),
                        "Solver auto: a fall-back starts from the last "
                        "iterate of the failed attempt (true) or from the "
                        "initial guess (false); after a non-finite value it "
                        "always starts from the initial guess. Unit: none.");
      prm.declare_entry("Auto settings",
                        d.auto_settings,
                        Selection("measured|given"),
                        "Solver auto: measured (default): the chain's "
                        "solvers get the settings measured best for the "
                        "problem's kind (lib/qp/README.md, doc/benchmarks/"
                        "membrane.md, section Defaults): MPRGP on bounds "
                        "with an assembled sparse Hessian (qpsolve) runs "
                        "with Gamma = 2, Expansion = projected-cg, 8 "
                        "Projected-CG trials, gradient factor 1.25, "
                        "Preconditioner = amg and Proportioning step = "
                        "preconditioned; a dense or matrix-free Hessian (the "
                        "contact dual, FCLIB) keeps the parameters of this "
                        "subsection. given: every solver of the chain runs "
                        "with the parameters of this subsection (the "
                        "thesis' table 14 unless set). Unit: none.");
      prm.declare_entry("Tolerance",
                        "1e-8",
                        Double(0., 1.),
                        "Stop when the stopping criterion's gradient norm is "
                        "at most Tolerance * ||b||. Unit: none (relative).");
      prm.declare_entry("Stopping criterion",
                        "projected",
                        Selection("projected|reduced|reduced-projected"),
                        "Gradient whose norm is tested (thesis 1.4): "
                        "projected g^P, reduced g~_alpha or reduced "
                        "projected g~^P_alpha with alpha = alpha_bar. The "
                        "reduced ones suit strongly curved sets (ellipses). "
                        "Unit: none.");
      prm.declare_entry("Maximum iterations",
                        std::to_string(d.max_iterations),
                        Integer(1),
                        "Iteration limit (all kinds of steps together); "
                        "reaching it is reported as not converged. "
                        "Unit: iterations.");
      prm.declare_entry("Stagnation window",
                        std::to_string(d.stagnation_window),
                        Integer(0),
                        "Report stagnation after this many iterations "
                        "without progress (0: never). Progress: a new "
                        "minimum of the criterion or, for the monotone "
                        "active-set solvers, a relative decrease of the "
                        "cost by more than 1e-12. Unit: iterations.");
      prm.declare_entry("Alpha bar factor",
                        "1.95",
                        Double(0., 2.),
                        "Fixed projection step alpha_bar = factor / "
                        "lambda_max (table 14: 1.95; convergence theory "
                        "needs (0, 2)). Unit: none.");
      prm.declare_entry("Gamma",
                        "1",
                        Double(0.),
                        "Proportioning constant Gamma > 0 of MPRGP, MPGP, "
                        "MPGP-BB: a CG step is taken while ||beta|| <= "
                        "Gamma ||phi|| (table 14: 1). Unit: none.");
      prm.declare_entry("Expansion",
                        d.expansion,
                        Selection("alpha-bar|projected-cg"),
                        "MPRGP and MPGP: the step after a CG half-step. "
                        "alpha-bar: thesis, the projected step of length "
                        "alpha_bar along the free gradient (MPRGP) or the "
                        "gradient (MPGP); projected-cg: the whole CG step "
                        "projected onto the set, which adds many "
                        "constraints at once (PERMON's projcg), replaced by "
                        "the alpha-bar step whenever it would not lower the "
                        "cost below that of the half-step. Unit: none.");
      prm.declare_entry("Projected-CG trials",
                        std::to_string(d.projected_cg_trials),
                        Integer(1),
                        "Expansion = projected-cg: the step lengths tried, "
                        "t_k = alpha_f + (alpha_cg - alpha_f) 2^-k for k = 0, "
                        "..., trials - 1 (alpha_f: the half-step), one Hessian "
                        "product each; the one of least cost is kept if that "
                        "is below the half-step's. 1: the whole CG step only "
                        "(PERMON's projcg). Unit: none.");
      prm.declare_entry(
        "Projected-CG gradient factor",
        "0",
        Double(0.),
        "Expansion = projected-cg with Projected-CG trials > 1: 0 keeps the "
        "trial of least cost; rho >= 1 keeps the least-cost trial among "
        "those below the half-step's cost whose projected gradient norm is "
        "at most rho times the least one among them (with a preconditioner "
        "in face the least-cost trial over-activates; benchmark B4: 1.25). "
        "Unit: none.");
      prm.declare_entry("Preconditioner",
                        d.preconditioner,
                        Selection("none|jacobi|amg|lumped|dirichlet"),
                        "MPRGP, MPGP and MPGP-BB: preconditioning in face "
                        "(Dostal 2009, sec. 5.10). The CG steps on the free "
                        "set use "
                        "z = M_F^{-1} phi, M_F a preconditioner of the "
                        "free-set block A_FF rebuilt whenever the active set "
                        "changes. none: plain MPRGP; jacobi: M_F = "
                        "diag(A)_FF (needs the problem's diagonal); amg: the "
                        "free-set preconditioner the problem supplies "
                        "(qpsolve: Trilinos ML AMG on A with the active rows "
                        "and columns replaced by identity rows); lumped: "
                        "TFETI's lumped preconditioner sum_s B_s K_s B_s' "
                        "(the free-set preconditioner of the TFETI dual); "
                        "dirichlet: TFETI's Dirichlet preconditioner "
                        "sum_s B_s S_s B_s', S_s the Schur complement of "
                        "K_s onto the dofs B_s touches (one more "
                        "factorization per subdomain). Unit: none.");
      prm.declare_entry(
        "Proportioning step",
        d.proportioning_step,
        Selection("chopped-gradient|preconditioned"),
        "MPRGP's proportioning step. chopped-gradient: thesis, steepest "
        "descent along the chopped gradient beta, cut at the bounds; "
        "preconditioned (needs a Preconditioner): the projected "
        "PCG step on the free set plus the unknowns beta releases, "
        "z = M^{-1}(phi + beta), lengths t0 = g'z/z'Az times 2^-k for "
        "k < Projected-CG trials, the least cost kept if below the cost "
        "after the chopped-gradient step, else that step. Unit: none.");
      prm.declare_entry("MPGP-BB memory",
                        "10",
                        Integer(0),
                        "MPGP-BB: a Barzilai-Borwein projection step is "
                        "accepted when the cost does not exceed the largest "
                        "cost before the last this-many BB steps; otherwise "
                        "it is redone with alpha_bar (a fall-back). 0 makes "
                        "the method monotone. Unit: steps.");
      prm.declare_entry("MwPGP delta",
                        "0.25",
                        Double(0., 0.5),
                        "delta in (0, 1/2) of the MwPGP proportioning test "
                        "2 delta ||g~^P||^2 <= ||phi||^2. Unit: none.");
      prm.declare_entry("PBBf K",
                        "10",
                        Integer(1),
                        "PBBf: number of non-monotone Barzilai-Borwein "
                        "steps before the fall-back test (table 14: 10). "
                        "Unit: iterations.");
      prm.declare_entry("SPG-QP m",
                        "10",
                        Integer(1),
                        "SPG-QP: memory of the non-monotone line search "
                        "(table 14: 10). Unit: iterations.");
      prm.declare_entry("SPG-QP gamma",
                        "0.1",
                        Double(0., 1.),
                        "SPG-QP: sufficient-decrease parameter gamma in "
                        "(0, 1) (table 14: 0.1). Unit: none.");
      prm.declare_entry("SPG-QP sigma2",
                        "0.9999",
                        Double(0., 1.),
                        "SPG-QP: safeguard sigma_2 in (0, 1) of the step "
                        "interval (table 14: 0.9999). Unit: none.");
      prm.declare_entry("SPG-QP alpha0 factor",
                        "1.95",
                        Double(0.),
                        "SPG-QP: first step alpha_0 = factor / lambda_max "
                        "(table 14: alpha_0 = alpha_bar). Unit: none.");
      prm.declare_entry("APGD L factor",
                        "1",
                        Double(0.),
                        "APGD: Lipschitz constant L = factor * lambda_max "
                        "(table 14: 1). Unit: none.");
      prm.declare_entry("Power iteration safety factor",
                        "1.05",
                        Double(1.),
                        "lambda_max estimated by power iteration is "
                        "multiplied by this (>= 1) so that alpha_bar stays "
                        "below 2 / lambda_max. Unit: none.");
      prm.declare_entry("Power iteration maximum iterations",
                        "100",
                        Integer(1),
                        "Iteration limit of the power iteration for "
                        "lambda_max. Unit: iterations.");
      prm.declare_entry("Power iteration tolerance",
                        "1e-4",
                        Double(0., 1.),
                        "Power iteration stops when the relative change of "
                        "the estimate is below this. Unit: none.");
      prm.leave_subsection();
    }


    void
    SolverParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("QP solver");
      solver    = prm.get("Solver");
      tolerance = prm.get_double("Tolerance");
      stopping_criterion =
        parse_stopping_criterion(prm.get("Stopping criterion"));
      max_iterations      = prm.get_integer("Maximum iterations");
      stagnation_window   = prm.get_integer("Stagnation window");
      alpha_bar_factor    = prm.get_double("Alpha bar factor");
      gamma               = prm.get_double("Gamma");
      expansion           = prm.get("Expansion");
      preconditioner      = prm.get("Preconditioner");
      proportioning_step  = prm.get("Proportioning step");
      projected_cg_trials = prm.get_integer("Projected-CG trials");
      projected_cg_gradient_factor =
        prm.get_double("Projected-CG gradient factor");
      mwpgp_delta         = prm.get_double("MwPGP delta");
      mpgp_bb_memory      = prm.get_integer("MPGP-BB memory");
      pbbf_k              = prm.get_integer("PBBf K");
      spg_m               = prm.get_integer("SPG-QP m");
      spg_gamma           = prm.get_double("SPG-QP gamma");
      spg_sigma2          = prm.get_double("SPG-QP sigma2");
      spg_alpha0_factor   = prm.get_double("SPG-QP alpha0 factor");
      apgd_l_factor       = prm.get_double("APGD L factor");
      power_safety_factor = prm.get_double("Power iteration safety factor");
      power_max_iterations =
        prm.get_integer("Power iteration maximum iterations");
      power_tolerance    = prm.get_double("Power iteration tolerance");
      auto_chain_bounds  = prm.get("Auto chain for bounds");
      auto_chain_general = prm.get("Auto chain for general sets");
      auto_warm_start    = prm.get_bool("Auto warm start");
      auto_settings      = prm.get("Auto settings");
      prm.leave_subsection();
      check();
    }


    void
    SolverParameters::check() const
    {
      const auto fail = [](const std::string &name, const std::string &why)
      {
        AssertThrow(false,
                    dealii::ExcMessage("Parameter `" + name +
                                       "' in `subsection QP solver': " + why));
      };
      if (!(tolerance > 0.))
        fail("Tolerance", "must be positive.");
      if (max_iterations < 1)
        fail("Maximum iterations", "must be at least 1.");
      if (!(alpha_bar_factor > 0. && alpha_bar_factor < 2.))
        fail("Alpha bar factor", "must lie in (0, 2).");
      if (!(gamma > 0.))
        fail("Gamma", "must be positive.");
      if (expansion != "alpha-bar" && expansion != "projected-cg")
        fail("Expansion",
             "must be alpha-bar or projected-cg (got '" + expansion + "').");
      if (projected_cg_trials < 1)
        fail("Projected-CG trials", "must be at least 1.");
      if (!(projected_cg_gradient_factor == 0. ||
            projected_cg_gradient_factor >= 1.))
        fail("Projected-CG gradient factor", "must be 0 (off) or at least 1.");
      if (preconditioner != "none" && preconditioner != "jacobi" &&
          preconditioner != "amg" && preconditioner != "lumped" &&
          preconditioner != "dirichlet")
        fail("Preconditioner",
             "must be none, jacobi, amg, lumped or dirichlet (got '" +
               preconditioner + "').");
      if (proportioning_step != "chopped-gradient" &&
          proportioning_step != "preconditioned")
        fail("Proportioning step",
             "must be chopped-gradient or preconditioned (got '" +
               proportioning_step + "').");
      if (proportioning_step == "preconditioned" && preconditioner == "none")
        fail("Proportioning step",
             "preconditioned needs Preconditioner = jacobi, amg, lumped or "
             "dirichlet.");
      if (!(mwpgp_delta > 0. && mwpgp_delta < 0.5))
        fail("MwPGP delta", "must lie in (0, 1/2).");
      if (pbbf_k < 1)
        fail("PBBf K", "must be at least 1.");
      if (spg_m < 1)
        fail("SPG-QP m", "must be at least 1.");
      if (!(spg_gamma > 0. && spg_gamma < 1.))
        fail("SPG-QP gamma", "must lie in (0, 1).");
      if (!(spg_sigma2 > 0. && spg_sigma2 < 1.))
        fail("SPG-QP sigma2", "must lie in (0, 1).");
      if (!(spg_alpha0_factor > 0.))
        fail("SPG-QP alpha0 factor", "must be positive.");
      if (!(apgd_l_factor > 0.))
        fail("APGD L factor", "must be positive.");
      if (!(power_safety_factor >= 1.))
        fail("Power iteration safety factor", "must be at least 1.");
      if (power_max_iterations < 1)
        fail("Power iteration maximum iterations", "must be at least 1.");
      if (!(power_tolerance > 0.))
        fail("Power iteration tolerance", "must be positive.");
      if (auto_settings != "measured" && auto_settings != "given")
        fail("Auto settings",
             "must be measured or given (got '" + auto_settings + "').");
      parse_chain(auto_chain_bounds, false, "Auto chain for bounds");
      parse_chain(auto_chain_general, true, "Auto chain for general sets");
    }


    std::vector<std::string>
    SolverParameters::parse_chain(const std::string &chain,
                                  const bool         general,
                                  const std::string &parameter)
    {
      std::vector<std::string> names;
      for (const std::string &item :
           dealii::Utilities::split_string_list(chain, ','))
      {
        const std::string name = dealii::Utilities::trim(item);
        if (name.empty())
          continue;
        const SolverRegistry &registry = SolverRegistry::instance();
        const SolverEntry    *entry    = registry.find(name);
        AssertThrow(entry != nullptr && entry->chainable,
                    dealii::ExcMessage(
                      "Parameter `" + parameter +
                      "' in `subsection QP solver': '" + name +
                      "' is not a solver a chain can hold (" +
                      join_names(registry.chainable_names(false)) + ")."));
        AssertThrow(!general ||
                      entry->accepted_sets == AcceptedSets::any_separable,
                    dealii::ExcMessage(
                      "Parameter `" + parameter +
                      "' in `subsection QP solver': " + name +
                      " takes bound and box constraints only, not discs, "
                      "ellipses or cones (" +
                      join_names(registry.chainable_names(true)) + ")."));
        names.push_back(name);
      }
      AssertThrow(!names.empty(),
                  dealii::ExcMessage("Parameter `" + parameter +
                                     "' in `subsection QP solver': the chain "
                                     "is empty; name at least one solver."));
      return names;
    }
  } // namespace qp
} // namespace dualcontact
