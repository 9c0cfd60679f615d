/**
 * @file solver_parameters.h
 * Every parameter of every QP solver, with the defaults of the thesis'
 * table 14, declared in the .prm subsection `QP solver`: the parameters
 * several solvers share at its level, those of one solver in a subsection
 * of it (`MPGP-BB`, `MwPGP`, `PBBf`, `SPG-QP`, `APGD`, `Auto`) and a
 * struct of their own.  One SolverParameters holds them all because the factory
 * hands the same parameters to whichever solver is selected, and the chain and
 * SMALSE-M pass them on to the solvers they run.
 */
#ifndef dualcontact_qp_solver_parameters_h
#define dualcontact_qp_solver_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <qp/solver_progress.h>
#include <util/enum_names.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace qp
  {
    /// Which gradient norm is compared with tol * ||b|| (thesis 1.4).
    enum class StoppingCriterion
    {
      /// ||g^P(x)||
      projected,
      /// ||g~_alpha(x)||, alpha = alpha_bar
      reduced,
      /// ||g~^P_alpha(x)||, alpha = alpha_bar
      reduced_projected
    };

    /// The names of StoppingCriterion: "projected", "reduced",
    /// "reduced_projected" (also spelt "reduced-projected").
    inline constexpr util::EnumNames<StoppingCriterion, 3, 1>
      stopping_criterion_names{
        "stopping criterion",
        {{"projected", "reduced", "reduced_projected"}},
        {{{StoppingCriterion::reduced_projected, "reduced-projected"}}},
      };

    /*
     * The parameters of one solver each, in their own subsection of `QP
     * solver`.  Declared here, not beside their solvers' classes, because
     * SolverParameters holds them by value (the factory, the chain and
     * SMALSE-M hand one object to whichever solver runs) and the solver
     * headers include this one.  Each: `subsection` (its name, which the
     * registry entry takes), declare_parameters() / parse_parameters()
     * inside that subsection (the registry enters it), check() naming the
     * parameter by its path.  The members' values are the .prm defaults.
     */

    /// MPGP-BB (`subsection QP solver/MPGP-BB`)
    struct MPGPBBParameters
    {
      static constexpr const char *subsection = "MPGP-BB";
      /// `Memory`: a Barzilai-Borwein projection is accepted when the cost
      /// does not exceed the largest cost before the last this-many BB
      /// attempts (non-monotone safeguard); 0 = monotone (every increase
      /// falls back to alpha_bar)
      unsigned int memory = 10;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(const dealii::ParameterHandler &prm);
      void
      check() const;
    };

    /// MwPGP (`subsection QP solver/MwPGP`)
    struct MwPGPParameters
    {
      static constexpr const char *subsection = "MwPGP";
      /// `Delta`: delta in (0, 1/2) of the MwPGP proportioning test
      /// 2 delta ||g~^P||^2 <= ||phi||^2
      double delta = 0.25;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(const dealii::ParameterHandler &prm);
      void
      check() const;
    };

    /// PBBf (`subsection QP solver/PBBf`)
    struct PBBfParameters
    {
      static constexpr const char *subsection = "PBBf";
      /// `K`: fall-back after K non-monotone steps (table 14: 10)
      unsigned int k = 10;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(const dealii::ParameterHandler &prm);
      void
      check() const;
    };

    /// SPG-QP (`subsection QP solver/SPG-QP`)
    struct SPGQPParameters
    {
      static constexpr const char *subsection = "SPG-QP";
      /// `m`: memory of the non-monotone line search (table 14: 10)
      unsigned int m = 10;
      /// `gamma`: sufficient decrease (table 14: 0.1)
      double gamma = 0.1;
      /// `sigma2`: safeguard sigma_2 (table 14: 0.9999)
      double sigma2 = 0.9999;
      /// `alpha0 factor`: alpha_0 = alpha0_factor / lambda_max (table 14:
      /// alpha_0 = alpha_bar, i.e. 1.95)
      double alpha0_factor = 1.95;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(const dealii::ParameterHandler &prm);
      void
      check() const;
    };

    /// APGD (`subsection QP solver/APGD`)
    struct APGDParameters
    {
      static constexpr const char *subsection = "APGD";
      /// `L factor`: L = l_factor * lambda_max (table 14: 1)
      double l_factor = 1.;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(const dealii::ParameterHandler &prm);
      void
      check() const;
    };

    /// The fall-back chain `auto` (`subsection QP solver/Auto`,
    /// solver_chain.h)
    struct AutoChainParameters
    {
      static constexpr const char *subsection = "Auto";
      /// `Chain for bounds`: the solvers tried in turn when every
      /// separable block is a bound or a box (comma-separated names,
      /// first = primary)
      std::string bounds = "mprgp, mpgp-bb, spg-qp";
      /// `Chain for general sets`: the solvers tried in turn when some
      /// block is a disc, ellipse or cone (mprgp not allowed: it takes
      /// bounds only)
      std::string general = "mpgp-bb, mpgp, spg-qp";
      /// `Warm start`: a fall-back starts from the previous attempt's last
      /// iterate (true) or from the initial guess (false); a non-finite
      /// iterate always restarts from the initial guess
      bool warm_start = true;
      /// `Settings`: "measured" (default): SolverChain::attempt_parameters
      /// gives each attempt the settings measured best for the problem's
      /// kind (Problem::hessian_storage): MPRGP on bounds with an
      /// assembled sparse Hessian and a free-set preconditioner factory
      /// runs with Gamma 2, projected-CG expansion with 8 trials and
      /// gradient factor 1.25, the AMG in face and the preconditioned
      /// release (benchmark B4, doc/benchmarks/membrane.md "Defaults
      /// (issue 20)"); every other case keeps the parameters given.
      /// "given": every attempt runs with the parameters given (the
      /// thesis' table 14 unless set).
      std::string settings = "measured";

      /// The checked names of `Chain for general sets` (@p general) or
      /// `Chain for bounds`.
      std::vector<std::string>
      chain(const bool general) const;

      /// The names of @p chain ("a, b, c"), checked: known, not `auto`,
      /// and no mprgp when @p general.  Throws naming @p parameter (a
      /// path such as "QP solver/Auto/Chain for bounds").
      static std::vector<std::string>
      parse_chain(const std::string &chain,
                  const bool         general,
                  const std::string &parameter);

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(const dealii::ParameterHandler &prm);
      void
      check() const;
    };


    struct SolverParameters
    {
      /// The default of `Solver` in the .prm: the fall-back chain.  The one
      /// parameter whose .prm default differs from the struct's (`solver`
      /// below, mprgp): a program that builds SolverParameters itself
      /// gets one plain solver, a .prm user the chain.
      static constexpr const char *prm_default_solver = "auto";
      /// mprgp | mpgp | mpgp-bb | mwpgp | spg-qp | pbbf | apgd | auto (the
      /// registry's names; auto: the fall-back chain of solver_chain.h).
      /// The .prm's default is prm_default_solver (auto).
      std::string solver = "mprgp";
      /// relative tolerance: stop when criterion <= tolerance * ||b||
      double            tolerance          = 1e-8;
      StoppingCriterion stopping_criterion = StoppingCriterion::projected;
      /// iteration limit (all kinds together); table 14: 1e4
      unsigned int max_iterations = 10000;
      /// stop with `stagnation` after this many iterations without
      /// progress: no new minimum of the criterion and (monotone
      /// active-set solvers) no relative cost decrease above 1e-12
      /// (0 = never)
      unsigned int stagnation_window = 1000;

      /// alpha_bar = alpha_bar_factor / lambda_max (table 14: 1.95); the
      /// fixed step of gradient projections/expansions
      double alpha_bar_factor = 1.95;
      /// Gamma > 0 of the proportioning test ||beta|| <= Gamma ||phi||
      /// (MPRGP, MPGP, MPGP-BB; table 14: 1)
      double gamma = 1.;
      /// The expansion after a CG half-step of MPRGP, MPGP and MPGP-BB:
      /// "alpha-bar" (thesis, algorithm 7: P(x_{k+1/2} - alpha_bar d),
      /// d = phi for MPRGP, g for MPGP; MPGP-BB's Barzilai-Borwein
      /// projection) or "projected-cg" (P(x_k - alpha_cg p), the whole CG
      /// step projected, PERMON's "projcg"; the method's own expansion is
      /// done instead when it would not lower the cost below that of the
      /// half-step).  Not used by MwPGP.
      std::string expansion = "alpha-bar";
      /// The projected-CG expansion tries the step lengths t_k = alpha_f
      /// + (alpha_cg - alpha_f) 2^-k, k = 0, ..., this - 1 (alpha_f the
      /// half-step), one Hessian product each, and keeps the one of least
      /// cost if that is below the half-step's.  1 = PERMON's projcg
      /// (the whole CG step only).  More trials pay off with a
      /// preconditioner in face, whose whole step overshoots the
      /// obstacle far.
      unsigned int projected_cg_trials = 1;
      /// With Projected-CG trials > 1: 0 keeps the trial of least cost;
      /// a factor rho >= 1 keeps the least-cost trial among those (below
      /// the half-step's cost) whose ||g^P|| is at most rho times the
      /// least ||g^P|| among them (one more Hessian product when that is
      /// not the least-cost trial).  With a preconditioner in face the
      /// least-cost trial over-activates a band around the contact zone,
      /// which proportioning then releases one grid line per step;
      /// benchmark B4 with rho = 1.25: 27 iterations at n = 10^6 against
      /// 14 at n = 2500 (doc/benchmarks/membrane.md).
      double projected_cg_gradient_factor = 0.;
      /// MPRGP with preconditioning in face (Dostal, Optimal Quadratic
      /// Programming Algorithms, 2009, sec. 5.10): the CG steps on the
      /// free set F use z = M_F^{-1} phi instead of phi, M_F a
      /// preconditioner of the free-set block A_FF, rebuilt whenever the
      /// active set changed (after an expansion or a proportioning step).
      /// "none" (plain MPRGP), "jacobi" (M_F = diag(A)_FF, from
      /// Problem::diagonal), "amg" (the operator returned by
      /// Problem::free_set_preconditioner for the active set; qpsolve
      /// builds Trilinos ML on A with the active rows and columns
      /// replaced by identity rows), "lumped" or "dirichlet" (the same
      /// factory; the TFETI dual supplies its lumped or its Dirichlet
      /// preconditioner there).  MPRGP, MPGP and MPGP-BB use it in their
      /// CG steps; the proportioning test and the expansions stay each
      /// solver's own.  MwPGP does not use it.
      std::string preconditioner = "none";
      /// MPRGP's proportioning step: "chopped-gradient" (thesis: steepest
      /// descent along beta, cut at the bounds) or, with a preconditioner
      /// in face, "preconditioned": the projected PCG step on F u R (R:
      /// the unknowns beta releases) from x, z = M_{F u R}^{-1}(phi +
      /// beta), lengths t0 = g'z / z'Az and t0 2^-k (k < Projected-CG
      /// trials), the least cost kept if below the cost after the
      /// chopped-gradient step, which is taken otherwise (so MPRGP's
      /// convergence argument holds).  It does the first PCG step on the
      /// enlarged face at once (benchmark B4: 86 -> 49 iterations at n =
      /// 10^6, doc/benchmarks/membrane.md).  MPRGP's alone, but kept at
      /// `QP solver` level with Preconditioner and Projected-CG trials,
      /// which it needs (lib/qp/README.md, "Parameters").
      std::string proportioning_step = "chopped-gradient";
      /// power iteration: returned estimate is safety_factor * estimate,
      /// so that alpha_bar stays below 2/lambda_max when it converged
      /// slowly from below
      double power_safety_factor = 1.05;
      /// power iteration: iteration limit
      unsigned int power_max_iterations = 100;
      /// power iteration: stop when the relative change of the estimate
      /// is below this
      double power_tolerance = 1e-4;

      /// The parameters of the solvers that have their own, each in its
      /// subsection of `QP solver` (declared and read through the
      /// solver's registry entry, solver_registry.h).  Every solver gets
      /// all of them: the chain and SMALSE-M hand one SolverParameters on.
      MPGPBBParameters    mpgp_bb;
      MwPGPParameters     mwpgp;
      PBBfParameters      pbbf;
      SPGQPParameters     spg;
      APGDParameters      apgd;
      AutoChainParameters auto_chain;

      /// Not a parameter of the .prm: what a program that wants to show
      /// progress during a long solve sets (see solver_progress.h).  Every
      /// solver made from these parameters (the chain's attempts,
      /// SMALSE-M's inner solver) calls it at its first checked iterate
      /// and then at most every `progress.interval` seconds; unset, no
      /// report is built.
      ProgressMonitor progress;

      /// Declare the shared parameters above in subsection `QP solver` of
      /// @p prm and, in a subsection of it each, the own parameters of
      /// every registered solver that has some (the registry's hooks).
      static void
      declare_parameters(dealii::ParameterHandler &prm);
      /// Read them back (enters and leaves the subsections itself);
      /// checks ranges and throws naming the parameter.
      void
      parse_parameters(dealii::ParameterHandler &prm);
      /// Throws (ExcMessage naming the parameter by its path, e.g.
      /// `QP solver/SPG-QP/m') on out-of-range values, the own parameters
      /// of every registered solver included.
      void
      check() const;
    };
  } // namespace qp
} // namespace dualcontact

#endif
