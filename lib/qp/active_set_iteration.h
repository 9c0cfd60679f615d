/**
 * @file active_set_iteration.h
 * One solve() of ActiveSetSolver: the problem, the iterate and every
 * quantity the steps share, with the steps of algorithm 7 (thesis, section
 * 2.4) as member functions in the thesis' order: the start gradient, the
 * proportionality test, the CG step or the feasible half-step with its
 * expansion (or the projected-CG trials in its place), MPRGP's
 * proportioning step (or the preconditioned release in its place), the
 * expansion of MPGP (alpha-bar or Barzilai-Borwein), the check of a
 * converged iterate.  Used by active_set_solver.cc only; the solvers'
 * interface is ActiveSetSolver (active_set_solver.h).
 */
#ifndef dualcontact_qp_active_set_iteration_h
#define dualcontact_qp_active_set_iteration_h

#include <qp/active_set_solver.h>
#include <qp/problem.h>
#include <qp/separable_set.h>
#include <qp/solver_statistics.h>

#include <chrono>
#include <deque>
#include <memory>
#include <string>

namespace dualcontact
{
  namespace qp
  {
    /**
     * The state of one ActiveSetSolver::solve() and its steps.  A step
     * that returns false has set stats.reason (breakdown, unbounded,
     * non-finite) and ends the loop.  The work vectors are the solver's
     * (kept between solves); the iteration holds references to them.
     */
    template <typename VectorType>
    class ActiveSetIteration
    {
    public:
      ActiveSetIteration(ActiveSetSolver<VectorType> &solver,
                         const Problem<VectorType>   &problem,
                         VectorType                  &x);

      /// The loop of algorithm 7 to the stopping test; the statistics.
      SolverStatistics
      run();

    private:
      using Clock = std::chrono::steady_clock;

      // ---- evaluations
      double
      cost_at(const VectorType &y, const VectorType &gy) const;
      double
      residual_and_cost(const VectorType &y, VectorType &gy) const;
      void
      recompute_gradient();
      double
      criterion_value();
      double
      refresh(VectorType &phi_out);
      bool
      proportional() const;

      // ---- the steps, in the order of algorithm 7
      void
      start_gradient();
      void
      barzilai_borwein_length();
      bool
      conjugate_gradient_or_half_step();
      bool
      conjugate_gradient_step(double alpha_cg, double pAp, double gp);
      bool
      step_along(double             dAd,
                 double             dd,
                 double             gd,
                 double             alpha_f,
                 const std::string &where,
                 const std::string &curvature,
                 const std::string &ray,
                 double            &alpha);
      void
      half_step_and_expansion(double alpha_f,
                              double alpha_cg,
                              double pAp,
                              double gp);
      bool
      projected_cg_expansion(double alpha_f, double alpha_cg, double f_half);
      void
      projection_step(double alpha);
      void
      expansion();
      bool
      proportioning_step();
      bool
      preconditioned_release(double alpha, double gb, double bAb);
      void
      verify_convergence();
      void
      finish();

      // ---- preconditioning in face and projected trials
      static double
      seconds(Clock::time_point start);
      void
      build_preconditioner();
      void
      update_preconditioner();
      void
      apply_preconditioner(const VectorType &in, VectorType &out);
      double
      projected_trial(VectorType       &y,
                      VectorType       &gy,
                      const VectorType &d,
                      double            t);
      void
      keep_trial();
      void
      take_kept_trial(double cost);

      ActiveSetSolver<VectorType> &solver;
      const SolverParameters      &prm;
      const std::string           &name;
      const ActiveSetVariant      &variant;
      const Problem<VectorType>   &problem;
      VectorType                  &x;

      // the caller's A x0 - b (Problem::start_gradient) replaces the first
      // product if the projection onto the set leaves x0 unchanged or
      // moves few unknowns (Problem::hessian_add_sparse)
      const bool       gradient_given;
      SolverStatistics stats;
      // Without constraints everything below still works with an empty
      // set.
      std::shared_ptr<const SeparableSet<VectorType>> set_ptr;
      const SeparableSet<VectorType>                 *set = nullptr;

      double lambda_max = 0.;
      double alpha_bar  = 0.;
      bool   weak       = false;

      // the work vectors (the solver's members, see there) in x's layout
      VectorType &g, &p, &Ap, &phi, &work;
      VectorType  x_prev, g_prev; // MPGP-BB only
      VectorType  x_best, g_best;
      // PERMON's "projcg" expansion (not with BB steps or MwPGP's test)
      bool projected_cg = false;

      // The cost f(x), kept by recurrences (a step x - a p changes it by
      // -a g'p + a^2/2 p'Ap) and recomputed with every new gradient; only
      // the stagnation test reads it.
      double f = 0.;
      // whether g is A x - b from a product (not from recurrences): then
      // the check of a converged iterate needs no new product, and the
      // KKT report takes g
      bool exact_gradient = false;

      double        bb_alpha = 0.;
      GradientNorms norms;
      // MPGP-BB's costs before its last BB attempts (the non-monotone
      // safeguard of expansion())
      std::deque<double> recent_costs;

      // Preconditioning in face (MPRGP, Dostal 2009, sec. 5.10): while
      // CG runs on a free set F the directions are built from z =
      // M_F^{-1} phi (zero on the active set) instead of phi, i.e. PCG on
      // A_FF; M_F is rebuilt when a restart finds another active set
      // than the one it was built for.  The test and the expansions stay
      // MPRGP's.
      bool preconditioned = false;
      // the preconditioned release step (Proportioning step =
      // preconditioned; SolverParameters::check() requires a
      // preconditioner for it)
      bool release_preconditioned = false;
      typename Problem<VectorType>::FreeSetPreconditioner free_set_inverse;
      VectorType mask, built_mask, z, Az;
      bool       have_preconditioner = false;
      // p holds phi after a restart; the preconditioned variant replaces it
      // by z = M_F^{-1} phi just before the first CG step that uses it
      bool restart_pending = true;

      // The current direction p and what the loop needs of it (filled by
      // conjugate_direction() after a CG step, so that the next step
      // needs one pass for p'Ap only); invalid after a restart.
      typename SeparableSet<VectorType>::Direction direction;
      bool                                         direction_valid = false;

      // the absolute stopping criterion at x after the last step
      double value = 0.;
    };
  } // namespace qp
} // namespace dualcontact

#endif
