#pragma once

#include <deal.II/lac/vector.h>

#include <contact/contact_solver.h>
#include <fclib/local_problem.h>
#include <qp/solver_parameters.h>
#include <qp/solver_statistics.h>

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
      cone
    };

    /** "coulomb" / "cone". */
    std::string
    to_string(const Model model);
    /** Accepts "coulomb", "cone"; throws otherwise. */
    Model
    parse_model(const std::string &name);

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

    /** "bonded" / "frictionless". */
    std::string
    to_string(const FirstIterate first);
    /** Accepts "bonded", "frictionless"; throws otherwise. */
    FirstIterate
    parse_first_iterate(const std::string &name);

    /**
     * Solves a LocalProblem with the project's QP solvers (any of
     * qp::solver_names() that accepts the blocks: mprgp only for mu = 0).
     * The QP Hessian is the symmetric part W_s = (W + W')/2 (1/2 r'W r only
     * sees it); a non-symmetric W (some distributed files) has its
     * antisymmetric part W_a taken at the previous iterate, u = W_s r +
     * W_a r^k + q, and the loop iterates until r^k is a fixed point, where
     * u = W r + q.  The FCLIB error is computed with W itself.  The Coulomb
     * loop follows contact::ContactSolver (bonded first iterate, relative
     * change of psi, divergence window), with the same parameters.
     */
    class LocalSolver
    {
    public:
      struct Result
      {
        bool        converged = false;
        std::string reason;
        /** One record per QP (Coulomb: per fixed-point iterate). */
        std::vector<qp::SolverStatistics> qp_statistics;
        /** Relative change of psi per Coulomb iterate. */
        std::vector<double> coulomb_changes;
        /**
         * Relative step ||r^{k+1} - r^k|| / ||r^{k+1}|| per iterate (with a
         * proximal term or a non-symmetric W).
         */
        std::vector<double> proximal_steps;
        /** Sum of the QP iterations. */
        unsigned long iterations = 0;
        /** Products with W (QPs and the power iteration). */
        unsigned long hessian_products = 0;
        /** The FCLIB accuracy measure of the result (fclib_error()). */
        double fclib_error = 0;
        double wall_time   = 0;
      };

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
       * iterate).
       *
       * With @p proximal = rho > 0 (constructor, relative to lambda_max(W))
       * every QP is regularized around the previous iterate r^k (proximal
       * point): minimize 1/2 r'W r + q'r + rho lambda_max/2 ||r - r^k||^2,
       * strictly convex and well conditioned even for singular W (rigid-body
       * problems, where the plain QPs converge slowly or are unbounded).  The
       * loop then also runs for the cone model and without friction, and
       * stops when both the change of psi and the step ||r^{k+1} - r^k|| /
       * ||r^{k+1}|| are below the Coulomb tolerance: a fixed point of the
       * regularized loop is a solution of the unregularized problem.
       */
      Result
      solve(dealii::Vector<double> &r) const;

    private:
      qp::SolverStatistics
      solve_qp(dealii::Vector<double>    &r,
               const std::vector<double> *psi,
               const double               lambda_max) const;

      /** rho of the proximal term, relative to lambda_max(W); 0: none. */
      double proximal_;
      /** Whether W is not symmetric (then the loop iterates on W_a r^k). */
      bool asymmetric_;

      const LocalProblem        &problem_;
      qp::SolverParameters       qp_parameters_;
      contact::CoulombParameters coulomb_parameters_;
      Model                      model_;
      FirstIterate               first_;
    };
  } // namespace fclib
} // namespace dualcontact
