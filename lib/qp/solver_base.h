/**
 * @file solver_base.h
 * Common base of all QP solvers: the solve() interface, and the
 * bookkeeping every solver shares (counted Hessian products, lambda_max,
 * the stopping criterion, stagnation / non-finite detection, final KKT
 * residuals), so that each algorithm's file contains only the algorithm.
 */
#ifndef dualcontact_qp_solver_base_h
#define dualcontact_qp_solver_base_h

#include <deal.II/base/timer.h>

#include <qp/problem.h>
#include <qp/solver_parameters.h>
#include <qp/solver_statistics.h>

#include <limits>
#include <string>

namespace dualcontact
{
  namespace qp
  {
    /**
     * Base class of the QP solvers.
     *
     * A derived solve() typically runs
     * @code
     *   SolverStatistics stats = start(problem, x);   // projects x, timer
     *   ...  apply_hessian(problem, dst, src, stats);  // counted
     *   ...  if (check_stop(stats, criterion_norm)) break;
     *   finish(problem, x, stats);                     // KKT, time
     *   return stats;
     * @endcode
     * A solver refuses (AssertThrow) problems it cannot handle at the start
     * of solve().
     */
    template <typename VectorType>
    class SolverBase
    {
    public:
      SolverBase(const std::string &name, const SolverParameters &parameters);
      virtual ~SolverBase() = default;

      /**
       * Solve @p problem.  @p x: in the initial guess (projected onto
       * Omega first if infeasible), out the last iterate.  Never throws
       * for a failed solve: the reason is in the returned statistics;
       * throws only for invalid input.
       */
      virtual SolverStatistics
      solve(const Problem<VectorType> &problem, VectorType &x) = 0;

      const std::string &
      name() const;
      const SolverParameters &
      parameters() const;

      /**
       * Change the relative tolerance and the iteration limit of the next
       * solves (checked like the parameters), so that a loop whose
       * tolerance follows its progress (the inexact Coulomb fixed point)
       * keeps one solver instead of creating and checking one per QP.
       */
      void
      set_tolerance(double tolerance, unsigned int max_iterations);

      /**
       * A x - b at the x the last solve() returned, if the solver ended
       * with it from a product at that very x (the active-set solvers do
       * after convergence), else nullptr.  For Problem::start_gradient of
       * a next QP with the same A and b.
       */
      const VectorType *
      final_gradient() const;

      /// ||Bx - c|| at the x the last solve() returned (0 for solvers
      /// without equality constraints: SMALSEM and SolverChain override).
      virtual double
      equality_residual() const;

    protected:
      /// Initialise the statistics (name, tolerance, ||b||), check the
      /// problem's consistency, project @p x onto Omega, start the timer.
      SolverStatistics
      start(const Problem<VectorType> &problem, VectorType &x);

      /// dst := A src, counted in @p stats.
      void
      apply_hessian(const Problem<VectorType> &problem,
                    VectorType                &dst,
                    const VectorType          &src,
                    SolverStatistics          &stats) const;

      /// x := P(x), counted in @p stats (no-op without constraints).
      void
      project(const Problem<VectorType> &problem,
              VectorType                &x,
              SolverStatistics          &stats) const;

      /// x := P(x - alpha g) in one pass (SeparableSet::projected_step),
      /// the projection counted in @p stats; x - alpha g without
      /// constraints.  @p g must not be @p x.
      void
      projected_step(const Problem<VectorType> &problem,
                     VectorType                &x,
                     const VectorType          &g,
                     double                     alpha,
                     SolverStatistics          &stats) const;

      /// lambda_max from the problem or by power iteration (counted);
      /// sets stats.lambda_max and stats.alpha_bar = factor / lambda_max.
      double
      lambda_max(const Problem<VectorType> &problem,
                 SolverStatistics          &stats) const;

      /// Absolute value of the selected criterion at x with gradient g
      /// (alpha = stats.alpha_bar for the reduced ones; needs lambda_max()
      /// to have been called for those).
      double
      criterion(const Problem<VectorType> &problem,
                const VectorType          &x,
                const VectorType          &g,
                const SolverStatistics    &stats) const;

      /**
       * Record the absolute criterion value @p value (divided by ||b||)
       * and decide whether to stop.  Returns true and sets stats.reason
       * when: the value is not finite (non_finite), it is <= tol
       * (converged), stats.iterations >= max_iterations (max_iterations),
       * or for stagnation_window iterations there was no progress
       * (stagnation).  Progress is a new minimum of the criterion, or,
       * when the solver passes a cost @p cost (the active-set solvers:
       * their iterate's; SPG-QP and PBBf: their iterate's, non-monotone),
       * a cost below the least cost at a progress
       * by more than a relative 1e-12.  (APGD passes none.)  The criterion of
       * the active-set solvers is not monotone: while the active set is being
       * found (thousands of expansions at n = 10^6) it may stay above its
       * minimum for long stretches in which the cost falls steadily, and
       * that is progress, not stagnation.  Call once per iteration, after
       * incrementing stats.iterations, and once before the first
       * iteration.
       */
      bool
      check_stop(SolverStatistics &stats,
                 double            value,
                 double cost = std::numeric_limits<double>::quiet_NaN());

      /// Call prm.progress with a ProgressReport on @p stats if one is due:
      /// at the first checked iterate of this solve, then every
      /// prm.progress.interval seconds.  check_stop() calls it; solvers
      /// that record criteria themselves (outer loops) call it too.
      void
      report_progress(const SolverStatistics &stats);

      /// Wall time since start() [s] (the time stamps of the history).
      double
      elapsed() const;

      /// Fill KKT residuals and wall time.
      void
      finish(const Problem<VectorType> &problem,
             const VectorType          &x,
             SolverStatistics          &stats);

      const std::string solver_name;
      SolverParameters  prm;
      /// see final_gradient(); start() clears the flag
      VectorType last_gradient;
      bool       last_gradient_valid = false;

    private:
      dealii::Timer timer;
      double        best_criterion     = 0.;
      double        cost_at_progress   = 0.;
      unsigned int  progress_iteration = 0;
      /// what report_progress() looks at: the problem and the iterate of
      /// the running solve (set by start()), and when to report next
      const Problem<VectorType> *progress_problem = nullptr;
      const VectorType          *progress_x       = nullptr;
      double                     next_report_time = 0.;
    };
  } // namespace qp
} // namespace dualcontact

#endif
