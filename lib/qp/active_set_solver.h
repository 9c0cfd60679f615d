/**
 * @file active_set_solver.h
 * The common engine of the thesis' active-set algorithms (algorithm 7,
 * section 2.4): conjugate gradients on the free set while the
 * proportioning test holds, feasible half-steps when CG would leave Omega,
 * and a "non-proportional" step otherwise.  MPRGP, MPGP, MPGP-BB and MwPGP
 * differ only in the proportioning test, the non-proportional step and the
 * step length of the expansion, so they are one loop with a Variant rather
 * than four copies of it.
 */
#ifndef dualcontact_qp_active_set_solver_h
#define dualcontact_qp_active_set_solver_h

#include <qp/solver_base.h>
#include <util/enum_names.h>

namespace dualcontact
{
  namespace qp
  {
    /// The published members of the MPGP family (thesis 2.4).
    enum class ActiveSetMethod
    {
      /// MPRGP (2.4.4) with the solvability test of MPRGPS (2.4.5)
      mprgp,
      /// MPGP (2.4.1, algorithm 7)
      mpgp,
      /// MPGP-BB (2.4.2)
      mpgp_bb,
      /// MwPGP (2.4.3)
      mwpgp
    };

    /// The solver names of ActiveSetMethod (the registry's keys).
    inline constexpr util::EnumNames<ActiveSetMethod, 4>
      active_set_method_names{
        "active-set method",
        {{"mprgp", "mpgp", "mpgp-bb", "mwpgp"}},
      };

    /// What distinguishes the members of the MPGP family.
    struct ActiveSetVariant
    {
      /// How to decide between a CG step and a non-proportional step.
      enum class Test
      {
        /// ||beta|| <= Gamma ||phi|| (MPRGP, MPGP, MPGP-BB; thesis 2.28)
        gamma,
        /// 2 delta ||g~^P_alpha||^2 <= ||phi||^2 (MwPGP; thesis 2.32)
        weak_reduced
      };
      /// What to do when the test fails.
      enum class Step
      {
        /// steepest descent along the chopped gradient, cut at the
        /// boundary (MPRGP's proportioning step, thesis 2.35)
        proportioning,
        /// gradient projection P(x - alpha g) (MPGP family, thesis 2.29)
        projection
      };

      Test test = Test::gamma;
      Step step = Step::projection;
      /// expansion after a half-step along the free gradient phi (MPRGP)
      /// instead of the full gradient g (MPGP)
      bool expand_with_free_gradient = false;
      /// Barzilai-Borwein step lengths in projections (MPGP-BB), with a
      /// fall-back to alpha_bar when the cost exceeds the largest of the
      /// last `mpgp_bb.memory` pre-step costs (non-monotone safeguard)
      bool barzilai_borwein = false;
      /// accept only bound and box blocks (MPRGP)
      bool bounds_only = false;

      /**
       * The variant of a published method:
       *  - MPRGP: gamma test, proportioning step, expansion along the free
       *    gradient, bound and box blocks only;
       *  - MPGP: gamma test, projection step;
       *  - MPGP-BB: MPGP with Barzilai-Borwein projections under the
       *    non-monotone safeguard of `QP solver/MPGP-BB/Memory' (one the
       *    thesis leaves out; memory 0 makes it monotone);
       *  - MwPGP: the weak test 2 delta ||g~^P_alpha||^2 <= ||phi||^2 on the
       *    reduced projected gradient (`QP solver/MwPGP/Delta'), projection
       *    step: for strongly curved sets (ill-conditioned ellipses).
       */
      static ActiveSetVariant
      of(const ActiveSetMethod method);
    };

    template <typename VectorType>
    class ActiveSetIteration;

    /**
     * Engine of the active-set solvers; ActiveSetVariant::of() gives the
     * published algorithms (the solver classes MPRGP, MPGP, MPGPBB, MwPGP
     * below).  With every variant:
     *  - a CG step whose curvature p'Ap is zero (relative to lambda_max
     *    ||p||^2) has alpha_cg = infinity; if the feasible step is
     *    infinite too the cost is unbounded below (the MPRGPS solvability
     *    test, thesis 2.4.5) and the solve stops with `unbounded`;
     *  - negative curvature (A not positive semidefinite) stops with
     *    `breakdown`;
     *  - equality constraints are refused (wrap in SMALSE-M).
     */
    template <typename VectorType>
    class ActiveSetSolver : public SolverBase<VectorType>
    {
    public:
      ActiveSetSolver(const std::string      &name,
                      const SolverParameters &parameters,
                      const ActiveSetVariant &variant);

      /// The published @p method under its name.
      ActiveSetSolver(const SolverParameters &parameters,
                      const ActiveSetMethod   method);

      SolverStatistics
      solve(const Problem<VectorType> &problem, VectorType &x) override;

    private:
      /**
       * The state of one solve() and its steps (algorithm 7 in the
       * thesis' order: start gradient, proportionality test, CG step or
       * feasible half-step with expansion, proportioning or expansion,
       * the check of a converged iterate); active_set_iteration.h.
       */
      friend class ActiveSetIteration<VectorType>;

      const ActiveSetVariant variant;
      /**
       * Work vectors, kept between solves: a loop of short QPs on a small
       * problem (the Coulomb fixed point of an FCLIB problem: 5-25 QPs of a
       * few iterations on a few hundred unknowns) would otherwise spend a
       * tenth of its time allocating them.  Their contents do not carry
       * over: each solve() writes them before reading.
       */
      VectorType g, p, Ap, phi, work, x_given;
    };

    /**
     * The solver class of a published @p method, constructed from the
     * parameters alone as the registry (solver_registry.h) creates solvers.
     */
    template <typename VectorType, ActiveSetMethod method>
    class ActiveSetMethodSolver : public ActiveSetSolver<VectorType>
    {
    public:
      explicit ActiveSetMethodSolver(const SolverParameters &parameters)
          : ActiveSetSolver<VectorType>(parameters, method)
      {
      }
    };

    /// MPRGP (thesis 2.4.4, with MPRGPS' solvability test of 2.4.5)
    template <typename VectorType>
    using MPRGP = ActiveSetMethodSolver<VectorType, ActiveSetMethod::mprgp>;
    /// MPGP (thesis 2.4.1, algorithm 7)
    template <typename VectorType>
    using MPGP = ActiveSetMethodSolver<VectorType, ActiveSetMethod::mpgp>;
    /// MPGP-BB (thesis 2.4.2)
    template <typename VectorType>
    using MPGPBB = ActiveSetMethodSolver<VectorType, ActiveSetMethod::mpgp_bb>;
    /// MwPGP (thesis 2.4.3)
    template <typename VectorType>
    using MwPGP = ActiveSetMethodSolver<VectorType, ActiveSetMethod::mwpgp>;
  } // namespace qp
} // namespace dualcontact

#endif
