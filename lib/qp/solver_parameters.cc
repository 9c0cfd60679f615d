#include <qp/solver_factory.h>
#include <qp/solver_parameters.h>
#include <qp/solver_registry.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace dualcontact
{
  namespace qp
  {
    namespace
    {
      /// The shortest text that reads back as @p value (fixed notation
      /// unless scientific is shorter, exponent without leading zeros:
      /// "1e-8", "0.9999", "1.95"): a default is written once, in the
      /// struct, and the .prm shows it as one would type it.
      std::string
      text(const double value)
      {
        for (int digits = 1; digits <= 17; ++digits)
        {
          char buffer[64];
          std::snprintf(buffer, sizeof(buffer), "%.*e", digits - 1, value);
          if (std::strtod(buffer, nullptr) != value)
            continue;
          const std::string scientific(buffer);
          const std::size_t e        = scientific.find('e');
          const int         exponent = std::atoi(scientific.c_str() + e + 1);
          const std::string short_scientific =
            scientific.substr(0, e) +
            (exponent == 0 ? "" : "e" + std::to_string(exponent));
          std::snprintf(buffer,
                        sizeof(buffer),
                        "%.*f",
                        std::max(digits - 1 - exponent, 0),
                        value);
          std::string fixed(buffer);
          if (fixed.find('.') != std::string::npos)
          {
            fixed.erase(fixed.find_last_not_of('0') + 1);
            if (fixed.back() == '.')
              fixed.pop_back();
          }
          return short_scientific.size() < fixed.size() ? short_scientific :
                                                          fixed;
        }
        return dealii::Utilities::to_string(value);
      }


      std::string
      text(const unsigned int value)
      {
        return std::to_string(value);
      }


      std::string
      text(const bool value)
      {
        return value ? "true" : "false";
      }


      /// The .prm spelling of @p criterion (a Selection entry).
      std::string
      prm_text(const StoppingCriterion criterion)
      {
        return criterion == StoppingCriterion::reduced_projected ?
                 "reduced-projected" :
                 stopping_criterion_names.name(criterion);
      }


      /// "QP solver/<subsection>/<entry>": how messages name an own
      /// parameter of a solver.
      std::string
      path(const std::string &subsection, const std::string &entry)
      {
        return "QP solver/" + subsection + "/" + entry;
      }


      /// Throws ExcMessage naming the parameter at @p parameter_path.
      void
      fail_parameter(const std::string &parameter_path, const std::string &why)
      {
        AssertThrow(false,
                    dealii::ExcMessage("Parameter `" + parameter_path +
                                       "': " + why));
      }
    } // namespace


    void
    SolverParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Bool;
      using dealii::Patterns::Double;
      using dealii::Patterns::Integer;
      using dealii::Patterns::Selection;
      const SolverParameters d;

      prm.enter_subsection("QP solver");
      prm.declare_entry("Solver",
                        prm_default_solver,
                        Selection(solver_names()),
                        "Algorithm for the QP with separable constraints "
                        "(thesis chapter 2; SMALSE-M around it when the "
                        "problem has equality constraints). " +
                          SolverRegistry::instance().descriptions() +
                          ". Unit: none.");
      prm.declare_entry("Tolerance",
                        text(d.tolerance),
                        Double(0., 1.),
                        "Stop when the stopping criterion's gradient norm is "
                        "at most Tolerance * ||b||. Unit: none (relative).");
      prm.declare_entry("Stopping criterion",
                        prm_text(d.stopping_criterion),
                        Selection("projected|reduced|reduced-projected"),
                        "Gradient whose norm is tested (thesis 1.4): "
                        "projected g^P, reduced g~_alpha or reduced "
                        "projected g~^P_alpha with alpha = alpha_bar. The "
                        "reduced ones suit strongly curved sets (ellipses). "
                        "Unit: none.");
      prm.declare_entry("Maximum iterations",
                        text(d.max_iterations),
                        Integer(1),
                        "Iteration limit (all kinds of steps together); "
                        "reaching it is reported as not converged. "
                        "Unit: iterations.");
      prm.declare_entry("Stagnation window",
                        text(d.stagnation_window),
                        Integer(0),
                        "Report stagnation after this many iterations "
                        "without progress (0: never). Progress: a new "
                        "minimum of the criterion or, for the monotone "
                        "active-set solvers, a relative decrease of the "
                        "cost by more than 1e-12. Unit: iterations.");
      prm.declare_entry("Alpha bar factor",
                        text(d.alpha_bar_factor),
                        Double(0., 2.),
                        "Fixed projection step alpha_bar = factor / "
                        "lambda_max (table 14: 1.95; convergence theory "
                        "needs (0, 2)). Unit: none.");
      prm.declare_entry("Gamma",
                        text(d.gamma),
                        Double(0.),
                        "Proportioning constant Gamma > 0 of MPRGP, MPGP, "
                        "MPGP-BB: a CG step is taken while ||beta|| <= "
                        "Gamma ||phi|| (table 14: 1). Unit: none.");
      prm.declare_entry("Expansion",
                        d.expansion,
                        Selection("alpha-bar|projected-cg"),
                        "MPRGP, MPGP and MPGP-BB: the step after a CG "
                        "half-step. alpha-bar: thesis, the projected step "
                        "of length alpha_bar along the free gradient "
                        "(MPRGP) or the gradient (MPGP), MPGP-BB's "
                        "Barzilai-Borwein projection; projected-cg: the "
                        "whole CG step projected onto the set, which adds "
                        "many constraints at once (PERMON's projcg), "
                        "replaced by the method's alpha-bar expansion "
                        "whenever it would not lower the cost below that of "
                        "the half-step. Unit: none.");
      prm.declare_entry("Projected-CG trials",
                        text(d.projected_cg_trials),
                        Integer(1),
                        "Expansion = projected-cg: the step lengths tried, "
                        "t_k = alpha_f + (alpha_cg - alpha_f) 2^-k for k = 0, "
                        "..., trials - 1 (alpha_f: the half-step), one Hessian "
                        "product each; the one of least cost is kept if that "
                        "is below the half-step's. 1: the whole CG step only "
                        "(PERMON's projcg). Unit: none.");
      prm.declare_entry(
        "Projected-CG gradient factor",
        text(d.projected_cg_gradient_factor),
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
      prm.declare_entry("Power iteration safety factor",
                        text(d.power_safety_factor),
                        Double(1.),
                        "lambda_max estimated by power iteration is "
                        "multiplied by this (>= 1) so that alpha_bar stays "
                        "below 2 / lambda_max. Unit: none.");
      prm.declare_entry("Power iteration maximum iterations",
                        text(d.power_max_iterations),
                        Integer(1),
                        "Iteration limit of the power iteration for "
                        "lambda_max. Unit: iterations.");
      prm.declare_entry("Power iteration tolerance",
                        text(d.power_tolerance),
                        Double(0., 1.),
                        "Power iteration stops when the relative change of "
                        "the estimate is below this. Unit: none.");
      // each solver's own parameters, in its subsection
      for (const SolverEntry &entry : SolverRegistry::instance().entries())
        if (!entry.parameter_subsection.empty())
        {
          prm.enter_subsection(entry.parameter_subsection);
          entry.declare_parameters(prm);
          prm.leave_subsection();
        }
      prm.leave_subsection();
    }


    void
    SolverParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("QP solver");
      solver    = prm.get("Solver");
      tolerance = prm.get_double("Tolerance");
      stopping_criterion =
        stopping_criterion_names.value(prm.get("Stopping criterion"));
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
      power_safety_factor = prm.get_double("Power iteration safety factor");
      power_max_iterations =
        prm.get_integer("Power iteration maximum iterations");
      power_tolerance = prm.get_double("Power iteration tolerance");
      for (const SolverEntry &entry : SolverRegistry::instance().entries())
        if (!entry.parameter_subsection.empty())
        {
          prm.enter_subsection(entry.parameter_subsection);
          entry.parse_parameters(prm, *this);
          prm.leave_subsection();
        }
      prm.leave_subsection();
      check();
    }


    void
    SolverParameters::check() const
    {
      const auto fail = [](const std::string &name, const std::string &why)
      { fail_parameter("QP solver/" + name, why); };
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
      if (!(power_safety_factor >= 1.))
        fail("Power iteration safety factor", "must be at least 1.");
      if (power_max_iterations < 1)
        fail("Power iteration maximum iterations", "must be at least 1.");
      if (!(power_tolerance > 0.))
        fail("Power iteration tolerance", "must be positive.");
      // each solver's own parameters, in the registry's order
      for (const SolverEntry &entry : SolverRegistry::instance().entries())
        if (entry.check_parameters)
          entry.check_parameters(*this);
    }


    // ------------------------------------------------------------ MPGP-BB

    void
    MPGPBBParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      const MPGPBBParameters d;
      prm.declare_entry("Memory",
                        text(d.memory),
                        dealii::Patterns::Integer(0),
                        "MPGP-BB: a Barzilai-Borwein projection step is "
                        "accepted when the cost does not exceed the largest "
                        "cost before the last this-many BB steps; otherwise "
                        "it is redone with alpha_bar (a fall-back). 0 makes "
                        "the method monotone. Unit: steps.");
    }


    void
    MPGPBBParameters::parse_parameters(const dealii::ParameterHandler &prm)
    {
      memory = prm.get_integer("Memory");
    }


    void
    MPGPBBParameters::check() const
    {
      // every unsigned value is valid (0: monotone)
    }


    // -------------------------------------------------------------- MwPGP

    void
    MwPGPParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      const MwPGPParameters d;
      prm.declare_entry("Delta",
                        text(d.delta),
                        dealii::Patterns::Double(0., 0.5),
                        "delta in (0, 1/2) of the MwPGP proportioning test "
                        "2 delta ||g~^P||^2 <= ||phi||^2. Unit: none.");
    }


    void
    MwPGPParameters::parse_parameters(const dealii::ParameterHandler &prm)
    {
      delta = prm.get_double("Delta");
    }


    void
    MwPGPParameters::check() const
    {
      if (!(delta > 0. && delta < 0.5))
        fail_parameter(path(subsection, "Delta"), "must lie in (0, 1/2).");
    }


    // --------------------------------------------------------------- PBBf

    void
    PBBfParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      const PBBfParameters d;
      prm.declare_entry("K",
                        text(d.k),
                        dealii::Patterns::Integer(1),
                        "PBBf: number of non-monotone Barzilai-Borwein "
                        "steps before the fall-back test (table 14: 10). "
                        "Unit: iterations.");
    }


    void
    PBBfParameters::parse_parameters(const dealii::ParameterHandler &prm)
    {
      k = prm.get_integer("K");
    }


    void
    PBBfParameters::check() const
    {
      if (k < 1)
        fail_parameter(path(subsection, "K"), "must be at least 1.");
    }


    // ------------------------------------------------------------- SPG-QP

    void
    SPGQPParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      const SPGQPParameters d;
      prm.declare_entry("m",
                        text(d.m),
                        dealii::Patterns::Integer(1),
                        "SPG-QP: memory of the non-monotone line search "
                        "(table 14: 10). Unit: iterations.");
      prm.declare_entry("gamma",
                        text(d.gamma),
                        dealii::Patterns::Double(0., 1.),
                        "SPG-QP: sufficient-decrease parameter gamma in "
                        "(0, 1) (table 14: 0.1). Unit: none.");
      prm.declare_entry("sigma2",
                        text(d.sigma2),
                        dealii::Patterns::Double(0., 1.),
                        "SPG-QP: safeguard sigma_2 in (0, 1) of the step "
                        "interval (table 14: 0.9999). Unit: none.");
      prm.declare_entry("alpha0 factor",
                        text(d.alpha0_factor),
                        dealii::Patterns::Double(0.),
                        "SPG-QP: first step alpha_0 = factor / lambda_max "
                        "(table 14: alpha_0 = alpha_bar). Unit: none.");
    }


    void
    SPGQPParameters::parse_parameters(const dealii::ParameterHandler &prm)
    {
      m             = prm.get_integer("m");
      gamma         = prm.get_double("gamma");
      sigma2        = prm.get_double("sigma2");
      alpha0_factor = prm.get_double("alpha0 factor");
    }


    void
    SPGQPParameters::check() const
    {
      if (m < 1)
        fail_parameter(path(subsection, "m"), "must be at least 1.");
      if (!(gamma > 0. && gamma < 1.))
        fail_parameter(path(subsection, "gamma"), "must lie in (0, 1).");
      if (!(sigma2 > 0. && sigma2 < 1.))
        fail_parameter(path(subsection, "sigma2"), "must lie in (0, 1).");
      if (!(alpha0_factor > 0.))
        fail_parameter(path(subsection, "alpha0 factor"), "must be positive.");
    }


    // --------------------------------------------------------------- APGD

    void
    APGDParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      const APGDParameters d;
      prm.declare_entry("L factor",
                        text(d.l_factor),
                        dealii::Patterns::Double(0.),
                        "APGD: Lipschitz constant L = factor * lambda_max "
                        "(table 14: 1). Unit: none.");
    }


    void
    APGDParameters::parse_parameters(const dealii::ParameterHandler &prm)
    {
      l_factor = prm.get_double("L factor");
    }


    void
    APGDParameters::check() const
    {
      if (!(l_factor > 0.))
        fail_parameter(path(subsection, "L factor"), "must be positive.");
    }


    // --------------------------------------------------------------- auto

    void
    AutoChainParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      const AutoChainParameters d;
      prm.declare_entry("Chain for bounds",
                        d.bounds,
                        dealii::Patterns::Anything(),
                        "Solver auto, every block a bound or box: the "
                        "solvers tried in this order, comma-separated; the "
                        "next runs only when the previous did not converge "
                        "(any reason). Unit: none.");
      prm.declare_entry("Chain for general sets",
                        d.general,
                        dealii::Patterns::Anything(),
                        "Solver auto, some block a disc, ellipse or cone: "
                        "the solvers tried in this order (not mprgp, which "
                        "takes bounds and boxes only). Unit: none.");
      prm.declare_entry("Warm start",
                        text(d.warm_start),
                        dealii::Patterns::Bool(),
                        "Solver auto: a fall-back starts from the last "
                        "iterate of the failed attempt (true) or from the "
                        "initial guess (false); after a non-finite value it "
                        "always starts from the initial guess. Unit: none.");
      prm.declare_entry("Settings",
                        d.settings,
                        dealii::Patterns::Selection("measured|given"),
                        "Solver auto: measured (default): the chain's "
                        "solvers get the settings measured best for the "
                        "problem's kind (lib/qp/README.md, doc/benchmarks/"
                        "membrane.md, section Defaults): MPRGP on bounds "
                        "with an assembled sparse Hessian (qpsolve) runs "
                        "with Gamma = 2, Expansion = projected-cg, 8 "
                        "Projected-CG trials, gradient factor 1.25, "
                        "Preconditioner = amg and Proportioning step = "
                        "preconditioned; a dense or matrix-free Hessian (the "
                        "contact dual, FCLIB) keeps the parameters of "
                        "`subsection QP solver'. given: every solver of the "
                        "chain runs with the parameters of `subsection QP "
                        "solver' (the thesis' table 14 unless set). Unit: "
                        "none.");
    }


    void
    AutoChainParameters::parse_parameters(const dealii::ParameterHandler &prm)
    {
      bounds     = prm.get("Chain for bounds");
      general    = prm.get("Chain for general sets");
      warm_start = prm.get_bool("Warm start");
      settings   = prm.get("Settings");
    }


    void
    AutoChainParameters::check() const
    {
      if (settings != "measured" && settings != "given")
        fail_parameter(path(subsection, "Settings"),
                       "must be measured or given (got '" + settings + "').");
      chain(false);
      chain(true);
    }


    std::vector<std::string>
    AutoChainParameters::chain(const bool general_set) const
    {
      return general_set ?
               parse_chain(general,
                           true,
                           path(subsection, "Chain for general sets")) :
               parse_chain(bounds, false, path(subsection, "Chain for bounds"));
    }


    std::vector<std::string>
    AutoChainParameters::parse_chain(const std::string &chain,
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
                      "Parameter `" + parameter + "': '" + name +
                      "' is not a solver a chain can hold (" +
                      join_names(registry.chainable_names(false)) + ")."));
        AssertThrow(!general ||
                      entry->accepted_sets == AcceptedSets::any_separable,
                    dealii::ExcMessage(
                      "Parameter `" + parameter + "': " + name +
                      " takes bound and box constraints only, not discs, "
                      "ellipses or cones (" +
                      join_names(registry.chainable_names(true)) + ")."));
        names.push_back(name);
      }
      AssertThrow(!names.empty(),
                  dealii::ExcMessage("Parameter `" + parameter +
                                     "': the chain is empty; name at least "
                                     "one solver."));
      return names;
    }
  } // namespace qp
} // namespace dualcontact
