#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/lapack_support.h>
#include <deal.II/lac/vector.h>

#include <fclib/local_problem.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace fclib
  {
    /**
     * The local FCLIB problem (fclib::LocalProblem) by the semismooth Newton
     * method on Alart and Curnier's equations, inside a proximal point loop:
     * the method of Siconos' PROX solver, written here from the
     * formulation (Alart and Curnier 1991; Christensen, Klarbring, Pang and
     * Stroemberg 1998 for the generalized Jacobian).
     *
     * Equations.  With u = W r + q and a scaling rho_i > 0 per contact
     * (rho_i = 1 / W_nn,i: forces and rho u in the same unit), z_i = r_i -
     * rho_i u_i and
     *
     *   Phi_i(r) = r_i - P_i(z_i),   P_i(z) = (max(z_n, 0),
     *              projection of z_t on the disc of radius mu_i max(z_n, 0)),
     *
     * Phi(r) = 0 is Coulomb's law with Signorini's condition on u_n: r_n >=
     * 0, u_n >= 0, r_n u_n = 0, ||r_t|| <= mu r_n, sticking where u_t = 0
     * and sliding against u_t where ||r_t|| = mu r_n, which is the FCLIB
     * problem (De Saxce's cone complementarity) written on the contacts.
     * Phi is piecewise smooth; its generalized Jacobian J = I - D (I - rho W),
     * D = dP/dz block diagonal (identity on sticking contacts, zero on open
     * ones, the disc's tangent projection on sliding ones), is sparse with
     * the pattern of W by contact rows: one sparse LU (UMFPACK) per Newton
     * step.  The step is damped by Armijo's rule on 1/2 ||Phi||^2.
     *
     * Proximal point.  A rigid-body W is singular (Capsules-i125-1213: rank
     * 570 of 858), and so is J on its sticking contacts.  The loop then
     * solves Phi = 0 for W + sigma I and q - sigma r^k (the proximal
     * problem at r^k, whose J is regular), takes its solution as r^{k+1}
     * and shrinks sigma by `Sigma reduction` while the Newton solves
     * converge; a fixed point r^{k+1} = r^k solves the problem itself.  A
     * regular W is tried without the proximal term first.
     *
     * Stops when the FCLIB error (fclib_error(), W itself) is at most the
     * tolerance, the measure Siconos' solvers stop on.
     */
    class NewtonSolver
    {
    public:
      struct Parameters
      {
        /** FCLIB error to reach [-]. */
        double tolerance = 1e-8;
        /** Newton steps in all (every proximal problem's together). */
        unsigned int max_steps = 500;
        /**
         * Try the plain method (no proximal term) first.  Off for a start
         * near the solution of a singular W (LocalSolver's polish: the
         * plain method cycled there for 20 steps on local_problem_test).
         */
        bool plain_first = true;
        /** Newton steps of one proximal problem before sigma grows. */
        unsigned int max_inner_steps = 20;
        /**
         * First sigma of the proximal loop, relative to the mean normal
         * diagonal entry of W [-].
         */
        double sigma = 1e-2;
        /**
         * sigma is multiplied by this after a converged Newton solve.  0.01
         * (was 0.1): on the 5 files that need the proximal loop at 1e-8,
         * 0.01 took the fewest steps in sum (Capsules 25, spheres-in-a-box
         * 51 against 36, 123 at 0.1; 0.003: spheres-in-a-box 252), the
         * counts erratic between neighbours (doc/fclib.md).
         */
        double sigma_reduction = 0.01;
        /** ... and never falls below this (relative, as sigma) [-]. */
        double sigma_min = 1e-10;
        /** Armijo's constant of the line search on 1/2 ||Phi||^2. */
        double armijo = 1e-4;
        /** Merits the non-monotone line search remembers (1: monotone). */
        unsigned int memory = 10;
        /** Extrapolate the proximal centers (Nesterov, with restart). */
        bool extrapolation = true;
        /** rho_i = rho_factor / W_nn,i [-]. */
        double rho_factor = 1.;
        /** Halvings of the step before the line search gives up. */
        unsigned int max_halvings = 30;

        /** Subsection `Newton` of fclibsolve's .prm. */
        static void
        declare_parameters(dealii::ParameterHandler &prm);
        void
        parse_parameters(dealii::ParameterHandler &prm);
        /** Throws (naming the parameter) on values out of range. */
        void
        check() const;
      };

      struct Result
      {
        bool        converged = false;
        std::string reason;
        /** Newton steps (= LU factorizations of J). */
        unsigned int steps = 0;
        /** Of these, the plain method's (before any proximal term). */
        unsigned int plain_steps = 0;
        /** Proximal problems solved (0: the plain Newton method did it). */
        unsigned int proximal_iterations = 0;
        /** Products with W (residual evaluations, line search included). */
        unsigned long products = 0;
        /** Trial points the line search rejected. */
        unsigned long halvings = 0;
        /** sigma / mean W_nn of each proximal problem. */
        std::vector<double> sigmas;
        /** FCLIB error after each proximal problem (or the plain solve). */
        std::vector<double> errors;
        double              fclib_error = 0;
        double              wall_time   = 0;
      };

      NewtonSolver(const LocalProblem &problem, const Parameters &parameters);
      ~NewtonSolver();
      NewtonSolver(const NewtonSolver &) = delete;
      NewtonSolver &
      operator=(const NewtonSolver &) = delete;

      /** @p r: the start on entry, the last iterate on exit. */
      Result
      solve(dealii::Vector<double> &r) const;

    private:
      /** How one Newton solve (one proximal problem) ended. */
      enum class Outcome
      {
        converged,
        singular,
        line_search_failed,
        step_limit
      };

      /**
       * Newton's method on Phi = 0 for W + sigma I and q - sigma @p center
       * from @p r, until the FCLIB error of the proximal problem is at most
       * @p tolerance.
       */
      Outcome
      newton(dealii::Vector<double>       &r,
             const dealii::Vector<double> &center,
             const double                  sigma,
             const double                  tolerance,
             Result                       &result) const;

      /** u = (W + sigma I) r + q - sigma center. */
      void
      velocity(dealii::Vector<double>       &u,
               const dealii::Vector<double> &r,
               const dealii::Vector<double> &center,
               const double                  sigma,
               Result                       &result) const;

      /**
       * Phi(r) for the velocity @p u; with @p D non-null also the
       * derivative blocks dP/dz (dim x dim per contact, row-major).
       */
      void
      residual(dealii::Vector<double>       &phi,
               const dealii::Vector<double> &r,
               const dealii::Vector<double> &u,
               std::vector<double>          *D) const;

      /**
       * Solves J x = -phi, J = I - D (I - rho (W + sigma I)), by UMFPACK;
       * false when J is singular.
       */
      bool
      solve_newton_system(const std::vector<double>    &D,
                          const double                  sigma,
                          const dealii::Vector<double> &phi,
                          dealii::Vector<double>       &x) const;

      /** x = -J^{-1} phi by LAPACK's dense LU of J (values_ scattered). */
      bool
      solve_dense(const dealii::Vector<double> &phi,
                  dealii::Vector<double>       &x) const;
      /** x = -J^{-1} phi by UMFPACK on J's pattern. */
      bool
      solve_sparse(const dealii::Vector<double> &phi,
                   dealii::Vector<double>       &x) const;

      /** The sparsity of J (CSR): W's rows merged by contact, plus the
       *  diagonal blocks. */
      void
      build_pattern();

      const LocalProblem &problem_;
      Parameters          parameters_;
      unsigned int        dim_;
      /** rho_i per contact. */
      std::vector<double> rho_;
      /** Mean normal diagonal entry of W (the unit of sigma). */
      double mean_normal_diagonal_ = 1;
      /** J's pattern, compressed rows (the rows of a contact share one
       *  column set). */
      std::vector<int> row_start_, columns_;
      /** Per row of J, W's entries of that row: (offset in the row's
       *  columns, value). */
      std::vector<std::vector<std::pair<unsigned int, double>>> w_rows_;
      /** Per row, the offset in its columns of its contact's first unknown
       *  (where the diagonal block starts). */
      std::vector<unsigned int> block_position_;
      /** J's values on the pattern (the last Jacobian assembled). */
      mutable std::vector<double> values_;
      /** UMFPACK's analysis of J's pattern (the first Jacobian's). */
      mutable void *symbolic_ = nullptr;
      /** Whether J is factorized dense (small or dense problems). */
      bool dense_ = false;
      /** The dense J (column-major) and its LU pivots. */
      mutable std::vector<double>                  dense_J_;
      mutable std::vector<dealii::types::blas_int> pivots_;
    };
  } // namespace fclib
} // namespace dualcontact
