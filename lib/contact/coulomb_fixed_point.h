/**
 * @file coulomb_fixed_point.h
 * Coulomb friction as a fixed point over Tresca problems: the parameters
 * (subsection `Coulomb`) and the bookkeeping every caller of the loop shares
 * (the dual ContactSolver, the primal primal::UzawaCGC, fclib's local
 * solver): the relative change of the slip bounds, the convergence,
 * divergence and limit tests, and one message for each way the loop ends.
 */
#ifndef dualcontact_contact_coulomb_fixed_point_h
#define dualcontact_contact_coulomb_fixed_point_h

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /** Parameters of the Coulomb fixed point, subsection `Coulomb`. */
    struct CoulombParameters
    {
      /** Stop when ||psi_new - psi_old|| <= tolerance ||psi_new|| [-]. */
      double tolerance = 1e-6;
      /** Limit on the fixed-point iterations (updates of psi). */
      unsigned int max_iterations = 50;
      /**
       * Declared divergent when the change grew in this many consecutive
       * iterations.
       */
      unsigned int divergence_window = 5;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };


    /**
     * The tests of the fixed point psi_{k+1} = mu lambda_N(psi_k): after
     * every update of the slip bounds the caller hands the relative change
     * to record_change(), which says whether to solve the next Tresca
     * problem.  The tests, in this order:
     * - a non-finite change stops (State::not_finite);
     * - a change at most CoulombParameters::tolerance converges;
     * - a change larger than the previous one in divergence_window
     *   consecutive updates diverges;
     * - the max_iterations-th update without convergence stops at the limit.
     * One Tresca problem is solved before the first update and one after
     * every update that says State::iterating, so a loop that reaches the
     * limit has solved max_iterations Tresca problems.
     */
    class CoulombFixedPoint
    {
    public:
      enum class State
      {
        /// solve the next Tresca problem
        iterating,
        converged,
        diverged,
        iteration_limit,
        not_finite
      };

      explicit CoulombFixedPoint(const CoulombParameters &parameters);

      /**
       * The relative change sqrt(change_squared / norm_squared) of psi, or
       * sqrt(change_squared) when psi is zero (a change from a non-zero psi
       * to zero is then not mistaken for convergence).
       */
      static double
      relative_change(double change_squared, double norm_squared);

      /** Record the relative change of the latest update; the new state. */
      State
      record_change(double relative_change);

      /** The relative changes recorded so far, one per update. */
      const std::vector<double> &
      changes() const;

      /**
       * Why the loop stopped, for a state other than iterating and
       * converged: "Coulomb fixed point diverged (...)", "... maximum
       * iterations (N) reached, relative change ...", "... non-finite slip
       * bounds"; "converged" and "" for the others.
       */
      std::string
      message() const;

    private:
      CoulombParameters   parameters;
      std::vector<double> recorded;
      unsigned int        growing = 0;
      State               current = State::iterating;
    };
  } // namespace contact
} // namespace dualcontact

#endif
