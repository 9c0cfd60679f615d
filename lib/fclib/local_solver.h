#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/vector.h>

#include <contact/contact_solver.h>
#include <fclib/local_problem.h>
#include <fclib/newton_solver.h>
#include <qp/solver_base.h>
#include <qp/solver_parameters.h>
#include <qp/solver_statistics.h>
#include <util/enum_names.h>

#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace fclib
  {
    /** How a local FCLIB problem is turned into QPs. */
    enum class Model
    {
      /**
       * Coulomb friction as the fixed point over Tresca QPs (the model of
       * lib/contact): minimize 1/2 r'W r + q'r with r_n >= 0 and ||r_t|| <=
       * psi_i (disc; box in 2D), psi_i = mu_i r_n,i of the previous iterate.
       * A fixed point solves the Coulomb problem exactly.
       */
      coulomb_fixed_point,
      /**
       * One second-order-cone QP: minimize 1/2 r'W r + q'r with r_i in the
       * Coulomb cone K_i.  This is a convex relaxation, not the Coulomb
       * problem: its optimality conditions put u = W r + q (not De Saxce's
       * u + mu ||u_t|| e_n) in the dual cone, i.e. sliding contacts separate
       * by mu ||u_t|| in the normal direction.  Its solution is the Coulomb
       * one only where nothing slides; the FCLIB error says how far it is.
       * 3D only (the library's cone block has 3 unknowns).
       */
      cone,
      /**
       * The cone QP with De Saxce's shift as a fixed point: minimize
       * 1/2 r'W r + (q + s)'r with r_i in K_i, s_i = mu_i ||u_t,i|| e_n at
       * the previous iterate (u = W r + q).  A fixed point solves the
       * Coulomb problem exactly (its conditions are De Saxce's).  3D only.
       */
      desaxce_fixed_point,
      /**
       * No QPs: the semismooth Newton method on Alart and Curnier's
       * equations inside a proximal point loop (fclib::NewtonSolver), which
       * solves the Coulomb problem exactly and stops on the FCLIB error.
       */
      newton
    };

    /** The names of Model: "coulomb", "cone", "desaxce", "newton". */
    inline constexpr util::EnumNames<Model, 4> model_names{
      "model",
      {{"coulomb", "cone", "desaxce", "newton"}},
    };

    /** The first iterate of the Coulomb fixed point from a zero start. */
    enum class FirstIterate
    {
      /**
       * No bound on r_t (as contact::ContactSolver): feasible for any load,
       * but unbounded below when W is singular along a tangential direction
       * that q pulls along (rigid-body problems).
       */
      bonded,
      /** psi = 0: the frictionless problem, bounded whenever a solution exists.
       */
      frictionless
    };

    /** The names of FirstIterate: "bonded", "frictionless". */
    inline constexpr util::EnumNames<FirstIterate, 2> first_iterate_names{
      "first Coulomb iterate",
      {{"bonded", "frictionless"}},
    };

    /** Whether the loop gets a proximal term. */
    enum class Proximal
    {
      off,
      on,
      /** the plain loop, and the proximal one if the plain loop fails */
      automatic
    };

    /**
     * Solves a LocalProblem with the project's QP solvers (any of
     * qp::solver_names() that accepts the blocks: mprgp only for mu = 0).
     *
     * The loop.  Model coulomb: the fixed point psi_i = mu_i r_n,i over
     * Tresca QPs (contact::ContactSolver's loop: bonded first iterate,
     * relative change of psi, divergence window, its parameters), each QP
     * warm started from the previous iterate.  The QP Hessian is the
     * symmetric part W_s = (W + W')/2 (1/2 r'W r only sees it); a
     * non-symmetric W has its antisymmetric part W_a taken at the previous
     * iterate, u = W_s r + W_a r^k + q.
     *
     * Inexact fixed point (like remark 7.3 of the 1996 report): the first
     * QPs are solved loosely, and the QP tolerance follows the progress of
     * the loop, eps_{k+1} = max(eps, min(eps_k, factor * change_k)), down
     * to the QP tolerance eps; the loop stops only after a QP solved to eps.
     * An early iterate whose bounds are about to change is not worth a tight
     * solve.
     *
     * Proximal point (singular W): every QP gets rho/2 ||r - r^k||^2, which
     * makes it strictly convex; r^{k+1} then solves the Coulomb problem
     * exactly for q perturbed by rho (r^{k+1} - r^k) (and, with lagged
     * W_a, by W_a (r^{k+1} - r^k)).  The loop stops when that perturbation
     * is at most the Coulomb tolerance times ||q|| and psi is a fixed point
     * to that tolerance: the same kind of relative criterion as the QPs'
     * (relative to ||b||), never the FCLIB error.  rho adapts: divided by
     * rho_factor when the QP took at most rho_decrease_below iterations
     * (cheap: the proximal term can be weaker, the loop faster),
     * multiplied by it when the QP took more than rho_increase_above
     * iterations (and the QP redone from r^k when it did not converge),
     * within [rho_min, rho_max] lambda_max.  Proximal::automatic (default)
     * runs the plain loop and, if it fails (a QP that does not converge —
     * typical of singular W, whose zero-curvature directions stall the
     * first-order QP solvers — or a loop that does not contract), the
     * proximal loop from the last iterate whose QP converged; a singular W
     * alone is no reason (many singular problems, e.g. with decoupled
     * unknowns, are solved faster by the plain loop).
     *
     * The FCLIB error of the result is computed with W itself.
     */
    class LocalSolver
    {
    public:
      /** The loop's options (fclibsolve's .prm, see declare_parameters()). */
      struct Parameters
      {
        Model        model = Model::coulomb_fixed_point;
        FirstIterate first = FirstIterate::bonded;

        /** Inexact fixed point: adapt the QP tolerance to the progress. */
        bool inexact = true;
        /** QP tolerance of the first QP (never below the QP tolerance). */
        double initial_qp_tolerance = 1e-2;
        /** eps_{k+1} = max(eps, min(eps_k, factor * change_k)). */
        double qp_tolerance_factor = 0.1;

        Proximal proximal = Proximal::automatic;
        /** Initial rho, relative to lambda_max(W). */
        double rho = 0.1;
        /** Adapt rho (else it stays at its initial value). */
        bool adaptive_rho = true;
        /** Range of rho, relative to lambda_max(W). */
        double rho_min = 1e-6, rho_max = 10.;
        /** rho is divided / multiplied by this. */
        double rho_factor = 2.;
        /** rho decreases after a QP of at most this many iterations. */
        unsigned int rho_decrease_below = 50;
        /**
         * rho increases after a QP of more than this many iterations.  150
         * (was 5000): spheres-in-a-box at 1e-8 (mpgp) 88213 products
         * instead of 129925 (75-500: 88-104k; 1000: 125k); no other file's
         * default run changes (doc/fclib.md, issue 20).
         */
        unsigned int rho_increase_above = 150;
        /**
         * Proximal point: extrapolate the center of the next QP,
         * y = r^k + beta_k (r^k - r^{k-1}) with Nesterov's beta_k, and
         * restart (beta = 0) when the step turns back (the gradient
         * restart of O'Donoghue and Candes).  The plain proximal point
         * contracts a direction of curvature lambda only by rho / (rho +
         * lambda) per QP; the extrapolated one by about 1 - sqrt(lambda /
         * rho), which is what the small curvatures of a rigid-body W need.
         */
        bool extrapolation = true;
        /**
         * Solve the QPs in r~_i = r_i / s_i, s_i = W_nn,i^-1/2 per contact
         * (one factor for a contact's unknowns: discs and cones keep their
         * shape, the QPs their solutions): a Jacobi scaling by contact.  The
         * normal diagonal of W of the Hertz exports spreads over a factor
         * 23-46 (nodes of different tributary area), which the first-order
         * QP solvers pay for in iterations.  Plain loop only (the proximal
         * QPs are solved unscaled).
         */
        bool contact_scaling = true;
        /**
         * Lanczos estimate of lambda_max (of S W_s S, and of W_s for rho):
         * it stops when the estimate changes by less than this relative
         * amount from one step to the next.  Lanczos converges to the
         * largest eigenvalue much faster than the power iteration, whose
         * tolerance (`Power iteration tolerance` of the QP solver, 1e-4)
         * would cost 1-2 more products for no change that matters: on the
         * Hertz and brick exports 1e-2 stops at 5 products with an
         * estimate within 1.2e-4 of the one at 1e-4 (7 products), which
         * the safety factor (1.05) covers.
         */
        double lanczos_tolerance = 1e-2;
        /**
         * Limit of the proximal loop's iterations (the larger of this and
         * the Coulomb limit): it takes many cheap steps.  Capsules at
         * --tol 1e-8 (Coulomb tolerance 1e-8) needs 1003 of them with mpgp
         * and up to 3873 with mpgp-bb (most of 1-3 QP iterations: the
         * fixed point on psi contracts slowly there, about 0.994 per
         * exact QP); 1000 stopped it just short (doc/fclib.md, issue 20).
         */
        unsigned int proximal_max_iterations = 5000;
        /**
         * Proximal::automatic: iteration limit of the plain loop's QPs (a
         * QP that stalls on a singular W is cut short; the Newton method
         * or the proximal loop takes over).
         * 1000 (was 2000): Capsules' first (bonded) QP never converges and
         * cost 2000 iterations; the largest plain QP that converges on the 8
         * FCLIB files takes 823 (spheres-in-a-box at 1e-8).
         * 500 (was 1000) since the Newton method follows a failed plain
         * loop: a stalled QP hands over to Newton sooner (Capsules at 1e-8
         * 35.5 -> 27.6 ms, spheres-in-a-box 166 -> 141 ms, the others
         * unchanged); with 250 PerioBox at 1e-8 and spheres-in-a-box at
         * 1e-4 leave the plain loop too (6.1 -> 14.6 ms, 22 -> 38 ms)
         * (doc/fclib.md, issue 20).
         */
        unsigned int auto_plain_qp_max_iterations = 500;
        /**
         * Proximal::automatic: iteration limit of the plain loop's bonded
         * QP (the first Coulomb iterate without slip bounds), which is
         * unbounded below when W is singular along a tangential direction
         * that q pulls along (Capsules: it never converges).  200: the
         * largest first QP that converges on the 8 FCLIB files and the 3
         * scene exports of scripts/bench_fclib takes 160
         * (spheres-in-a-box); Capsules at 1e-8 then hands over to Newton
         * after 200 instead of 500 iterations (doc/fclib.md, issue 20).
         */
        unsigned int auto_bonded_qp_max_iterations = 200;
        /**
         * Proximal::automatic: after a failed plain loop, the semismooth
         * Newton method (NewtonSolver, with `newton`'s settings, to an
         * FCLIB error at most the Coulomb tolerance) before the proximal
         * QP loop, which runs only if Newton fails too.  The plain loop
         * fails on the rigid-body files whose Coulomb fixed point contracts
         * slowly (Capsules, spheres-in-a-box); there Newton takes 36 / 123
         * steps where the proximal QP loop took 1,004 / 897 QPs
         * (doc/fclib.md, issue 20).
         */
        bool newton_after_plain_loop = true;
        /**
         * Model coulomb: a converged loop whose solution's FCLIB error is
         * above the Coulomb tolerance (the loop stops on relative QP and
         * fixed-point criteria, not on that error: local_problem_test at
         * --tol 1e-8 ended at 1.7e-8, Hertz L3 at 1e-4 at 1.3e-4) is
         * refined: a dense W by the plain loop once more with QPs ten times
         * tighter (a Newton step there is a dense LU: 0.85 ms on Hertz L3
         * against 0.36 ms for the whole loop), a sparse one by proximal
         * Newton steps.
         */
        bool polish = true;
        /** The Newton method's settings (subsection `Newton`). */
        NewtonSolver::Parameters newton;

        /** Top-level entries of fclibsolve's .prm. */
        static void
        declare_parameters(dealii::ParameterHandler &prm);
        void
        parse_parameters(dealii::ParameterHandler &prm);
        /** Throws (naming the parameter) on values out of range. */
        void
        check() const;
        /** "off", "on", "auto", or a number (> 0: on with that rho). */
        void
        parse_proximal(const std::string &value);
      };

      struct Result
      {
        bool        converged = false;
        std::string reason;
        /** One record per QP (Coulomb: per fixed-point iterate). */
        std::vector<qp::SolverStatistics> qp_statistics;
        /** Relative change of psi per Coulomb iterate. */
        std::vector<double> coulomb_changes;
        /**
         * ||rho (r^{k+1} - r^k) + W_a (r^{k+1} - r^k)|| / ||q|| per iterate
         * (with a proximal term or a non-symmetric W): how far q is from
         * the problem r^{k+1} solves exactly.
         */
        std::vector<double> perturbations;
        /** rho / lambda_max per iterate (proximal loop). */
        std::vector<double> rhos;
        /** Whether the proximal term was on, and why. */
        bool        proximal = false;
        std::string proximal_reason;
        /** The Newton method after a failed plain loop (steps 0: not run). */
        NewtonSolver::Result newton;
        /** Newton steps / QPs of the polish (0: not needed or off). */
        unsigned int polish_steps = 0, polish_qps = 0;
        /** The last iterate whose QP converged (empty: none yet). */
        dealii::Vector<double> last_good;
        /** Sum of the QP iterations. */
        unsigned long iterations = 0;
        /** Products with W (QPs and the power iteration). */
        unsigned long hessian_products = 0;
        /** Of these, the power iteration's (0 when lambda_max was known). */
        unsigned long power_products = 0;
        /** The FCLIB accuracy measure of the result (fclib_error()). */
        double fclib_error = 0;
        double wall_time   = 0;
      };

      LocalSolver(const LocalProblem               &problem,
                  const qp::SolverParameters       &qp_parameters,
                  const contact::CoulombParameters &coulomb_parameters,
                  const Parameters                 &parameters);

      /** With the default Parameters but @p model, @p first and a fixed
       * proximal rho (0: off) — the options of the first version. */
      LocalSolver(const LocalProblem               &problem,
                  const qp::SolverParameters       &qp_parameters,
                  const contact::CoulombParameters &coulomb_parameters,
                  const Model                       model,
                  const FirstIterate first    = FirstIterate::bonded,
                  const double       proximal = 0.);

      /**
       * @p r: the start on entry (zero: cold start, the first Coulomb
       * iterate as chosen by FirstIterate; otherwise the bounds come from
       * it), the solution on exit (also when not converged: the last
       * iterate).  lambda_max(W) and the rank test are done on the first
       * call and reused by later ones.
       */
      Result
      solve(dealii::Vector<double> &r) const;

    private:
      /**
       * The loop from @p r, plain or with the proximal term; appends to
       * @p result (QP records, changes), sets converged and reason.
       * @p polish: every QP at a tenth of the QP tolerance from the first
       * (polish_by_qps()).
       */
      void
      run_loop(dealii::Vector<double> &r,
               const bool              proximal,
               Result                 &result,
               const bool              polish = false) const;

      /**
       * Proximal::automatic after a failed plain loop: the Newton method
       * from @p start to an FCLIB error at most the Coulomb tolerance
       * (result.newton); true, with @p r its solution and result converged,
       * if it converged (else @p r is left as it was).
       */
      /** Parameters::newton with the Coulomb tolerance as its FCLIB error
       *  goal (the fallback's and the polish's). */
      NewtonSolver::Parameters
      newton_to_coulomb_tolerance() const;

      bool
      solve_by_newton(const dealii::Vector<double> &start,
                      dealii::Vector<double>       &r,
                      Result                       &result) const;

      /** Parameters::polish for a sparse W: Newton steps from the converged @p
       * r to the Coulomb tolerance on the FCLIB error; @p r replaced if they
       * get there. */
      void
      polish_by_newton(dealii::Vector<double> &r, Result &result) const;
      /** Parameters::polish for a dense W: the plain loop from @p r with
       *  QPs ten times tighter; @p r replaced if its error is smaller. */
      void
      polish_by_qps(dealii::Vector<double> &r, Result &result) const;

      /** The state of one run_loop() (local_solver.cc). */
      struct Loop;

      /** The iteration limit of @p loop's next QP (auto: the plain and
       *  bonded caps). */
      unsigned int
      qp_iteration_limit(const Loop &loop) const;

      /** The loop's kind, limits and first iterate's bounds (psi, or
       *  bonded) from the start @p r; lambda_max(W_s) for the proximal
       *  term on its first use. */
      Loop
      start_loop(const dealii::Vector<double> &r,
                 const bool                    proximal,
                 const bool                    polish,
                 Result                       &result) const;
      /** De Saxce's shift mu_i ||u_t,i|| per contact at @p x (u = W x + q). */
      std::vector<double>
      desaxce_shift(const dealii::Vector<double> &x) const;
      /** shift_ := the shift @p s on the normal components. */
      void
      set_shift(const std::vector<double> &s) const;
      /** The Tresca slip bounds mu_i max(x_n,i, 0) of the iterate @p x. */
      std::vector<double>
      slip_bounds(const dealii::Vector<double> &x) const;
      /** Appends the QP record @p s to @p result; whether it converged. */
      static bool
      record(const qp::SolverStatistics &s, Result &result);
      /** The proximal center r := r^k + beta (r^k - r^{k-1}) (Nesterov). */
      void
      extrapolate_center(Loop &loop, dealii::Vector<double> &r) const;
      /** After a proximal QP that failed in iteration @p it: rho stronger,
       *  r back to the previous iterate; false when rho cannot grow. */
      bool
      retry_with_stronger_rho(Loop                   &loop,
                              const unsigned int      it,
                              dealii::Vector<double> &r,
                              Result                 &result) const;
      /** The reason of a loop that stops on a failed QP. */
      void
      report_qp_failure(const Loop        &loop,
                        const unsigned int it,
                        Result            &result) const;
      /** ||rho (r - r^k) + W_a (r - r^k)|| / ||q|| (recorded), and the
       *  extrapolation's gradient restart. */
      double
      proximal_perturbation(Loop                         &loop,
                            const dealii::Vector<double> &r,
                            Result                       &result) const;
      /** psi from the new iterate @p r; the relative change (recorded). */
      double
      update_slip_bounds(Loop                         &loop,
                         const dealii::Vector<double> &r,
                         Result                       &result) const;
      /** True, with the reason set, when the iterate is non-finite or the
       *  loop converged. */
      bool
      converged_or_non_finite(Loop        &loop,
                              const double change,
                              const double perturbation,
                              Result      &result) const;
      /** The inexact loop's next QP tolerance and the adaptive rho. */
      void
      adapt_tolerance_and_rho(Loop              &loop,
                              const double       progress,
                              const unsigned int qp_iterations,
                              Result            &result) const;
      /** True, with the reason set, when the Coulomb loop diverges or the
       *  iteration limit is reached. */
      bool
      diverged_or_exhausted(Loop              &loop,
                            const unsigned int it,
                            const double       change,
                            const double       perturbation,
                            Result            &result) const;

      /**
       * lambda_max of @p hessian by Lanczos from q, with the QP solver's
       * limit and safety factor and the Lanczos tolerance; its products
       * are added to @p result.
       */
      double
      estimate_lambda_max(
        const std::function<void(dealii::Vector<double> &,
                                 const dealii::Vector<double> &)> &hessian,
        Result &result) const;

      /** dst = S W_s S src (the contact-scaled QPs' Hessian). */
      void
      scaled_vmult(dealii::Vector<double>       &dst,
                   const dealii::Vector<double> &src) const;

      qp::SolverStatistics
      solve_qp(dealii::Vector<double>    &r,
               const std::vector<double> *psi,
               const double               rho,
               const double               tolerance,
               const unsigned int         max_iterations) const;

      /** Whether W is not symmetric (then the loop iterates on W_a r^k). */
      bool asymmetric_;

      const LocalProblem        &problem_;
      qp::SolverParameters       qp_parameters_;
      contact::CoulombParameters coulomb_parameters_;
      Parameters                 parameters_;
      /** lambda_max(W_s) (0: not yet estimated). */
      mutable double lambda_max_ = 0;
      /** lambda_max of the plain QPs' S W_s S (W_s without scaling). */
      mutable double qp_lambda_max_ = 0;
      /** Contact scaling s per unknown (empty: none; plain loop only). */
      dealii::Vector<double> scale_;
      /** De Saxce's shift s (normal entries; model desaxce). */
      mutable dealii::Vector<double> shift_;
      /** S W_s S formed once when W is dense and small (else empty). */
      std::vector<double> scaled_W_;
      /** S src for scaled_vmult() without scaled_W_. */
      mutable dealii::Vector<double> scale_work_;
      /** The QP solver (its tolerance and limit set per QP). */
      mutable std::unique_ptr<qp::SolverBase<dealii::Vector<double>>> solver_;
      /**
       * The last QP's set and its shape per contact (see solve_qp()): the
       * next QP of the same shape changes the radii only.
       */
      mutable std::shared_ptr<qp::SeparableSet<dealii::Vector<double>>> set_;
      mutable std::vector<unsigned char> set_shape_;
      /**
       * The end of the last plain QP (no proximal or lagged term, so the
       * next has the same Hessian and b): the solution r as returned, the
       * solver's unknowns x (scaled if end_scaled_) and A x - b there;
       * empty gradient when the last QP was not plain or did not end with
       * an exact gradient.
       */
      mutable dealii::Vector<double>                  end_r_, end_x_;
      mutable std::shared_ptr<dealii::Vector<double>> end_gradient_;
      mutable bool                                    end_scaled_ = false;
    };
  } // namespace fclib
} // namespace dualcontact
