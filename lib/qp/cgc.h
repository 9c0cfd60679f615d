/**
 * @file cgc.h
 * CGC: the conjugate projected gradient method with facet restarts for
 *   minimize 1/2 x'Cx - b'x  subject to  a_i'x <= c_i,  i = 1..M
 * of Kestranek & Nedoma (1996 report, sections 6-7), with the
 * loose-then-strict inner tolerance of remark 7.3 and the preconditioned
 * variant PCG-2 of section 9.
 *
 * Why a separate solver with its own problem type: the primal baseline of
 * the report (Uzawa over friction multipliers, lib/primal) has constraints
 * that couple unknowns (a row per contact node pair) and a Hessian that is
 * the stiffness matrix itself, so it is not a separable QP.  The method
 * minimizes f on the facet {a_j'x = c_j, j in J} of the currently active
 * constraints by CG on the projected gradient (I - P_J) f', stops at the
 * first constraint it hits (the facet grows), and when the facet problem is
 * solved leaves the facet of a constraint with a negative multiplier (the
 * facet shrinks).  Finite termination follows from the finite number of
 * facets and the finite termination of CG on each.
 */
#ifndef dualcontact_qp_cgc_h
#define dualcontact_qp_cgc_h

#include <qp/linear_inequalities.h>
#include <qp/solver_statistics.h>
#include <util/enum_names.h>

#include <functional>
#include <memory>
#include <vector>

namespace dualcontact
{
  namespace qp
  {
    /// The QP that CGC solves: Hessian C (SPD, or SPS with the cost bounded
    /// on the feasible set) as an operator, linear term b, rows A x <= c.
    template <typename VectorType>
    struct CGCProblem
    {
      /// dst := C src
      std::function<void(VectorType &dst, const VectorType &src)> hessian;
      VectorType                                                  b;
      std::shared_ptr<const LinearInequalities>                   constraints;
    };


    /**
     * The CGC solver.
     *
     * Statistics: `iterations` counts CG steps (one Hessian product each),
     * `n_cg` full CG steps, `n_half_steps` steps cut at a new constraint
     * (the facet grows), `n_proportioning` facet releases (constraints
     * dropped for a negative multiplier), `n_outer` the outer iterations of
     * subroutine CGC, `n_projections` the facet projections P_J.  The
     * criterion (recorded once per outer iteration) is
     *   sqrt(||(I - P_J) g||^2 + sum_{j in J} min(u_j, 0)^2 ||a_j||^2),
     * u the multipliers of the active set J; for bound constraints this is
     * exactly ||g^P|| of the thesis, so CGC compares with the other
     * solvers.  KKT residuals: stationarity = that criterion, feasibility
     * = ||max(Ax - c, 0)||, complementarity = sum_{j in J} |u_j| slack_j.
     */
    template <typename VectorType>
    class CGC
    {
    public:
      using size_type = dealii::types::global_dof_index;
      /// dst := M src for a preconditioner piece
      using Operator = std::function<void(VectorType &, const VectorType &)>;

      /// How many constraints leave the facet when the facet problem is
      /// solved and several multipliers are negative.
      enum class Release
      {
        /// the most negative (report, section 7, after lemma 7.1)
        one,
        /// all negative ones (lemma 7.2: safe for orthogonal rows)
        all_negative,
        /// all_negative if the rows are mutually orthogonal, else one
        automatic
      };

      /// How the tolerances are read.
      enum class StoppingTest
      {
        /// relative to ||b||: the criterion (above) at most tolerance ||b||
        /// ends the solve, a facet problem is solved when ||(I - P_J) g||
        /// is at most the (loose or strict) tolerance times ||b||, and a
        /// multiplier is negative when it is below zero
        relative,
        /// the report's tests with epsilon = tolerance (loose_tolerance in
        /// the first n_loose outer iterations, remark 7.3), in the units
        /// of the problem: subroutine CG returns when ||(I - P_J) g||^2 <
        /// epsilon or the relative step ||x^{k+1} - x^k|| / max(1,
        /// ||x^k||) < epsilon; subroutine CGC takes a facet problem as
        /// solved when pg^{IT+1} / max(1, pg^{IT}) < epsilon (pg^{IT} =
        /// ||(I - P_J) g|| at the start of outer iteration IT, remark 7.2)
        /// and a multiplier u_i as negative when u_i / max(1, max_J u) <
        /// -epsilon; the solve ends on a solved facet without negative
        /// multipliers
        report
      };

      struct AdditionalData
      {
        /// stop when the criterion <= tolerance * ||b|| (StoppingTest::
        /// relative; the report's epsilon with StoppingTest::report)
        double tolerance = 1e-8;
        /// limit on CG steps (Hessian products)
        unsigned int max_iterations = 10000;
        /// remark 7.3: during the first n_loose outer iterations a facet
        /// problem counts as solved at loose_tolerance * ||b|| ...
        double       loose_tolerance = 1e-2;
        unsigned int n_loose         = 10;
        /// ... afterwards at strict_factor * tolerance * ||b||
        double  strict_factor = 0.5;
        Release release       = Release::automatic;
        /// a constraint is active when its slack is at most
        /// active_tolerance * (|c_i| + sum_k |a_ik x_k|)
        double active_tolerance = 1e-12;
        /// report's dd test: return from CG when the relative step
        /// ||x^{k+1} - x^k|| / max(1, ||x^k||) is below this
        double       step_tolerance = 1e-15;
        StoppingTest stopping_test  = StoppingTest::relative;
        /// stop with `stagnation` if the criterion has not reached a new
        /// minimum for this many CG steps (0 = never)
        unsigned int stagnation_window = 2000;
        /// relative tolerance and limit of the CG solve for the facet
        /// multipliers (A_J A_J') u = -A_J g when rows are not orthogonal
        double       projection_tolerance      = 1e-13;
        unsigned int projection_max_iterations = 1000;
      };

      /// The names of StoppingTest (`Primal solver/CGC stopping test').
      static constexpr util::EnumNames<StoppingTest, 2> stopping_test_names{
        "CGC stopping test",
        {{"relative", "report"}},
      };

      /// The names of Release (`Primal solver/CGC release').
      static constexpr util::EnumNames<Release, 3> release_names{
        "CGC release",
        {{"one", "all negative", "automatic"}},
      };

      explicit CGC(const AdditionalData &data = AdditionalData());

      /**
       * PCG with a symmetric preconditioner W^{-1} (dst := W^{-1} src):
       * search directions from (I - P_J) W^{-1} (I - P_J) g, i.e. PCG-2
       * with E^{-T}E^{-1} applied as one operator.  Use this with a
       * deal.II preconditioner (wrap its vmult).
       */
      void
      set_preconditioner(const Operator &apply_inverse);

      /**
       * The report's PCG-2 (section 9) with W = E E' given by its factors:
       * g = (I-P) E^{-1} (I-P) r, direction -(I-P) E^{-T} g.  This is how
       * the report applies diagonal (E = D^{1/2}), SSOR and (in)complete
       * Cholesky preconditioning.
       */
      void
      set_split_preconditioner(const Operator &apply_E_inverse,
                               const Operator &apply_E_inverse_transpose);

      /// no preconditioning (the default)
      void
      clear_preconditioner();

      /**
       * Solve.  @p x: in an initial guess (rows with one entry -- bounds --
       * are enforced on it; any other violated row is an error: CGC needs
       * a feasible start, report remark 7.1 uses x = 0 with c >= 0), out
       * the last iterate.  Never throws for a failed solve (see the
       * reason); throws for invalid input.
       */
      SolverStatistics
      solve(const CGCProblem<VectorType> &problem, VectorType &x);

      /// Active rows at the returned x and their multipliers u_j (>= 0 at
      /// a solution): the contact forces of the primal baseline.
      const std::vector<std::pair<size_type, double>> &
      multipliers() const;

      /// One outer iteration of subroutine CGC (the rows of the report's
      /// tables 11.3-11.10).
      struct OuterRecord
      {
        /// constraints active at the start of the outer iteration
        unsigned int n_active = 0;
        /// constraints kept on the facet the CG run minimizes over (fewer
        /// than n_active after a release)
        unsigned int n_facet = 0;
        /// CG steps (Hessian products) of that CG run
        unsigned int inner_iterations = 0;
      };

      /// The outer iterations of the last solve().
      const std::vector<OuterRecord> &
      outer_log() const;

    private:
      AdditionalData                            data;
      Operator                                  preconditioner;
      Operator                                  e_inverse;
      Operator                                  e_inverse_transpose;
      std::vector<std::pair<size_type, double>> final_multipliers;
      std::vector<OuterRecord>                  outer_records;
    };
  } // namespace qp
} // namespace dualcontact

#endif
