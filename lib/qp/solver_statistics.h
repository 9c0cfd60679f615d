/**
 * @file solver_statistics.h
 * The one record every QP solver fills.  All solvers report through the same
 * structure so that the driver, qpsolve and the benchmarks can compare them
 * without knowing which algorithm ran.
 */
#ifndef dualcontact_qp_solver_statistics_h
#define dualcontact_qp_solver_statistics_h

#include <nlohmann/json_fwd.hpp>
#include <util/enum_names.h>

#include <ostream>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace qp
  {
    /**
     * Why a solver stopped.  Only `converged` means that the stopping
     * criterion was met; everything else is a failure and must be reported as
     * such.
     */
    enum class ConvergenceReason
    {
      /// the chosen criterion fell below tol * ||b||
      converged,
      /// the iteration limit was reached first
      max_iterations,
      /// the criterion has not improved for a long time (see SolverParameters)
      stagnation,
      /// a quantity the algorithm divides by vanished or changed sign
      /// (e.g. p'Ap <= 0 with an SPD Hessian)
      breakdown,
      /// NaN or Inf in the iterate, gradient or criterion
      non_finite,
      /// the (SPS) problem has no solution: the cost is unbounded below on
      /// the feasible set (MPRGPS solvability test, thesis 2.4.5)
      unbounded
    };

    /// The names of ConvergenceReason in JSON and console output.
    inline constexpr util::EnumNames<ConvergenceReason, 6>
      convergence_reason_names{
        "convergence reason",
        {{"converged",
          "max_iterations",
          "stagnation",
          "breakdown",
          "non_finite",
          "unbounded"}},
      };

    /// convergence_reason_names.name(reason), e.g. "max_iterations".
    std::string
    to_string(ConvergenceReason reason);

    /**
     * Final KKT residuals, absolute (divide by SolverStatistics::norm_b for
     * relative values).  See compute_kkt_residuals() for the definitions.
     */
    struct KKTResiduals
    {
      /// ||g^P(x)||: the gradient minus the best non-negative combination of
      /// outward normals of active blocks (and the equality part, if any)
      double stationarity = 0.;
      /// ||x - P(x)|| (plus ||Bx - c|| with equality constraints)
      double feasibility = 0.;
      /// sum over blocks of (multiplier estimate) * (distance to the block's
      /// boundary); zero at a KKT point
      double complementarity = 0.;
    };

    /**
     * Work counts, timing and outcome of one solve.
     *
     * Iterations are counted once each in `iterations`, and once by kind:
     * a CG step, a feasible half-step (CG step cut at the boundary followed
     * by a fixed-step projection), an expansion / gradient projection step,
     * a proportioning step, a Barzilai-Borwein step, a fall-back step.  A
     * solver that has no notion of a kind leaves it at zero.
     */
    struct SolverStatistics
    {
      /// name the solver was created with ("mprgp", ...)
      std::string solver;
      /// "projected", "reduced" or "reduced_projected"
      std::string stopping_criterion;
      /// relative tolerance the criterion was compared with
      double tolerance = 0.;

      ConvergenceReason reason = ConvergenceReason::max_iterations;
      /// free text with details of a failure (empty on success)
      std::string message;
      /// the settings the solver ran with, where a caller chose them
      /// (the chain `auto`, SolverChain::describe_settings: "gamma=2,
      /// expansion=projected-cg, ..."); empty otherwise
      std::string settings;

      unsigned int iterations      = 0;
      unsigned int n_cg            = 0;
      unsigned int n_half_steps    = 0;
      unsigned int n_expansions    = 0;
      unsigned int n_proportioning = 0;
      unsigned int n_bb            = 0;
      unsigned int n_fall_back     = 0;
      /// MPRGP with Proportioning step = preconditioned: proportioning
      /// steps done as the preconditioned release (the rest of
      /// n_proportioning are MPRGP's own)
      unsigned int n_preconditioned_releases = 0;
      /// outer iterations of an outer loop (SMALSE-M), 0 otherwise
      unsigned int  n_outer            = 0;
      unsigned long n_hessian_products = 0;
      unsigned long n_projections      = 0;
      /// preconditioning in face (MPRGP, `Preconditioner` not none): how
      /// often M_F was built (once per new active set), the wall time of
      /// those builds, how often M_F^{-1} was applied and the wall time of
      /// the applications (both included in wall_time)
      unsigned int  n_preconditioner_setups       = 0;
      double        preconditioner_setup_time     = 0.;
      unsigned long n_preconditioner_applications = 0;
      double        preconditioner_apply_time     = 0.;

      /// wall time of solve() in seconds
      double wall_time = 0.;
      /// ||b|| the relative criterion refers to (1 if b = 0)
      double norm_b = 0.;
      /// lambda_max used for the step lengths (0 if none was needed)
      double lambda_max = 0.;
      /// fixed projection step length alpha_bar used (0 if none)
      double alpha_bar = 0.;

      /// relative criterion ||g_*|| / ||b|| at every checked iterate,
      /// history[0] at the initial guess
      std::vector<double> history;
      /// per entry of `history`: the wall time since solve() started [s],
      /// and the iterations and Hessian products counted so far, so that a
      /// convergence history can be charted against time and work (the
      /// iteration count is not the entry's index for solvers that record
      /// only some iterates, e.g. SMALSE-M's outer loop)
      std::vector<double>        history_time;
      std::vector<unsigned int>  history_iterations;
      std::vector<unsigned long> history_products;
      /// last relative criterion value
      double final_criterion = 0.;
      /// absolute KKT residuals at the returned x
      KKTResiduals kkt;

      /// The solver chain (`auto`, solver_chain.h): one record per solver
      /// tried, in order; empty for a single solver.  The record holding
      /// them describes the returned iterate (reason, criterion and KKT of
      /// the last attempt; work counts and time summed over all attempts).
      std::vector<SolverStatistics> attempts;
      /// index into `attempts` of the attempt whose iterate was returned
      /// (the first that converged, else the last); -1 without attempts
      int chosen_attempt = -1;

      /// Append the relative criterion @p relative to `history`, with the
      /// time stamp @p seconds and the current iteration and product counts.
      /// Does not touch final_criterion.
      void
      record_criterion(const double relative, const double seconds);

      /// Remove the last entry of the history (a value that a recomputation
      /// supersedes).
      void
      drop_last_criterion();

      /// Add the step counts of @p inner, a solve run inside this one
      /// (SMALSE-M's inner solves, the attempts of `auto`): iterations and
      /// their kinds, projections, the free-set preconditioner's setups,
      /// applications and times.  Not the outer iterations and Hessian
      /// products, which SMALSE-M counts itself.
      void
      add_step_counts(const SolverStatistics &inner);

      /// True only if the reason is `converged` AND the final criterion is
      /// at most the tolerance: a record cannot claim success otherwise.
      bool
      converged() const;

      /// Write the record (without the history arrays unless
      /// @p with_history) as JSON.
      void
      write_json(std::ostream &out, const bool with_history = true) const;

      /// The record as a JSON string.
      std::string
      to_json(const bool with_history = true) const;
    };

    /// @p value for JSON, which has no Inf or NaN: the number where it is
    /// finite, else its text ("inf", "nan"), so nothing is lost.
    nlohmann::json
    json_number(const double value);
  } // namespace qp
} // namespace dualcontact

#endif
