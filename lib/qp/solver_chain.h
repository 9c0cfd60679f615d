/**
 * @file solver_chain.h
 * The solver `auto`: a solver chosen by the constraint types, and the next
 * one of a fixed chain when it does not converge.
 *
 * Why: no single algorithm of this library converges on every contact QP
 * the application meets (the stability matrix, doc/stability.md): MPRGP is
 * fastest on bound constraints but only takes bounds, the active-set
 * solvers can run into their iteration limit or stagnate on badly scaled
 * duals where a spectral projected-gradient method still makes progress.
 * A user who does not know which one suits a scene gets the fast one first
 * and an honest, recorded fall-back instead of a failed run.
 */
#ifndef dualcontact_qp_solver_chain_h
#define dualcontact_qp_solver_chain_h

#include <qp/smalse_m.h>
#include <qp/solver_base.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace qp
  {
    /**
     * Runs the solvers of a chain one after the other until one converges.
     *
     * Policy (lib/qp/README.md, "The solver chain auto"):
     * - the chain is AutoChainParameters::bounds (SolverParameters::
     *   auto_chain, `subsection QP solver/Auto`) when every block of the
     *   separable set is a bound or a box (or there is no set), and
     *   AutoChainParameters::general otherwise (discs, ellipses,
     *   cones);
     * - with equality constraints every attempt is SMALSE-M around the
     *   chain's solver (with the SMALSE-M parameters given here);
     * - an attempt that ends with any reason but `converged` hands over to
     *   the next solver; each attempt gets the full iteration limit;
     * - warm start (AutoChainParameters::warm_start, default true): the
     *   next attempt starts from the last iterate of the failed one (a
     *   feasible point nearer the solution; every solver of the chain
     *   converges from any feasible start), except after a non-finite
     *   value, when it starts from the caller's initial guess.
     *
     * Statistics: the returned record is named "auto", holds one record
     * per attempt in SolverStatistics::attempts and the index of the
     * returned one in chosen_attempt (the first that converged, else the
     * last).  Its reason, message, criterion, history and KKT residuals are
     * those of the chosen attempt, so it is converged() only if that
     * attempt converged; iterations, products, projections and time are
     * summed over all attempts (the work the chain did).
     */
    template <typename VectorType>
    class SolverChain : public SolverBase<VectorType>
    {
    public:
      SolverChain(
        const SolverParameters  &parameters,
        const SMALSEMParameters &smalse_parameters = SMALSEMParameters());

      /// The solver names the chain tries on @p problem, in order
      /// (without the SMALSE-M wrapping).
      std::vector<std::string>
      chain(const Problem<VectorType> &problem) const;

      /**
       * The parameters the attempt with solver @p name gets on @p problem:
       * the chain's own parameters with `solver = name`, and, with
       * `Auto/Settings = measured` (the default), the settings measured best
       * for the problem's kind (doc/benchmarks/membrane.md, "Defaults (issue
       * 20)"):
       * - MPRGP without equality constraints on an assembled sparse
       *   Hessian (Problem::hessian_storage == sparse_matrix) whose
       *   problem supplies a free-set preconditioner factory: Gamma = 2,
       *   Expansion = projected-cg, 8 Projected-CG trials, gradient factor
       *   1.25, Preconditioner = amg, Proportioning step = preconditioned
       *   (membrane, PERMON's variant, h = 50 ... 800: 9 to 35 iterations,
       *   against 244 to 7708 for PERMON's best MPGP setting);
       * - MPRGP on an assembled sparse Hessian without such a factory:
       *   Gamma = 2 and Expansion = projected-cg (PERMON's best setting;
       *   the membrane at h = 400: 2947 iterations against 10,000+ with
       *   the thesis' defaults);
       * - MPGP-BB and MPGP on a problem with constraints and unknowns
       *   outside them (TFETI's dual, whose gluing and Dirichlet
       *   multipliers are free): Expansion = projected-cg, and Gamma = 2
       *   for MPGP-BB (brick 20 x 40 x 20 in 16 subdomains, 1e-6: 776
       *   Hessian products against 1265; MPGP 4883 against 6734);
       * - everything else (a dense Hessian: the contact dual F, FCLIB's
       *   W; an operator without free unknowns; the other solvers): the
       *   parameters given.
       * The measured settings replace only the thesis' table-14 values:
       * when any of Gamma, Expansion, Projected-CG trials, Projected-CG
       * gradient factor, Preconditioner and Proportioning step differs
       * from them, every attempt runs with the parameters given (and
       * its `auto_chain.settings` says "given").
       */
      SolverParameters
      attempt_parameters(const Problem<VectorType> &problem,
                         const std::string         &name) const;

      /// "measured: gamma=2, expansion=projected-cg, ..." (or "given:
      /// ..."): the settings of @p parameters that @p parameters.solver
      /// uses (MPRGP: Gamma, expansion, trials, gradient factor,
      /// preconditioner, proportioning step; MPGP and MPGP-BB: the first
      /// four; others: the thesis' table-14 parameters, not
      /// listed), as SolverStatistics::settings of each attempt.
      static std::string
      describe_settings(const SolverParameters &parameters);

      /// The parameters of the attempt whose record the last solve()
      /// returned (SolverStatistics::chosen_attempt).
      const SolverParameters &
      chosen_parameters() const;

      SolverStatistics
      solve(const Problem<VectorType> &problem, VectorType &x) override;

      /// ||Bx - c|| at the returned x (0 without equality constraints)
      double
      equality_residual() const override;

    private:
      SMALSEMParameters smalse_prm;
      double            last_equality_residual = 0.;
      SolverParameters  last_parameters;
    };
  } // namespace qp
} // namespace dualcontact

#endif
