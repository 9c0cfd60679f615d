/**
 * @file augmented_lagrangian.h
 * The augmented Lagrangian of SMALSE-M's outer loop (thesis 2.5,
 * algorithm 8) and the bound-constrained inner problem it hands to the
 * inner solver.  Used by smalse_m.cc only; the solver's interface is SMALSEM
 * (smalse_m.h).
 */
#ifndef dualcontact_qp_augmented_lagrangian_h
#define dualcontact_qp_augmented_lagrangian_h

#include <qp/problem.h>
#include <qp/solver_parameters.h>
#include <qp/solver_statistics.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * L(x, lambda, rho) = f(x) + lambda'(Bx - c) + rho/2 ||Bx - c||^2 for
     * the problem SMALSE-M's outer loop works on: f(x) = 1/2 x'Ax - b'x or,
     * with the coarse projector P = I - B'B, 1/2 x'PAPx - x'P(b - A x0),
     * x0 = B'c (the class documentation of SMALSEM says why).  It holds the
     * multiplier lambda (zero at the start) and the work vectors; every
     * product with A is counted in the statistics it is given.
     */
    template <typename VectorType>
    class AugmentedLagrangian
    {
    public:
      /// @p problem must have equality constraints with both products;
      /// @p coarse_projector: work with P A P (the rows of B orthonormal);
      /// @p x gives the layout of the unknown-sized vectors.
      AugmentedLagrangian(const Problem<VectorType> &problem,
                          const bool                 coarse_projector,
                          const double               rho,
                          const VectorType          &x,
                          SolverStatistics          &stats);

      /**
       * The inner problem: minimize 1/2 x'(A + rho B'B)x - x'b over the
       * problem's separable set, b set by inner_right_hand_side(); its
       * lambda_max from @p lambda_max_A where a bound is known (else a
       * power iteration with the settings of @p prm) and its free-set
       * preconditioner from the problem's.  Its functions refer to this
       * object: use it only while this object lives.
       */
      Problem<VectorType>
      inner_problem(const double lambda_max_A, const SolverParameters &prm);

      /// The inner right-hand side b - B'lambda + rho B'c.
      void
      inner_right_hand_side(VectorType &inner_b);

      /// ||Bx - c||; keeps Bx - c for update_multipliers().
      double
      equality_residual(const VectorType &x);

      /// L(x, lambda, rho).
      double
      value(const VectorType &x);

      /// The gradient of L(., lambda, rho) at @p x: Ax - b + B'(lambda +
      /// rho (Bx - c)), the gradient at the updated multiplier.
      const VectorType &
      gradient(const VectorType &x);

      /// Step 2 of algorithm 8: lambda += rho (Bx - c).
      void
      update_multipliers(const VectorType &x);

      /// lambda
      const VectorType &
      multipliers() const;

    private:
      /// v := P v = v - B'B v
      void
      project(VectorType &v);

      /// dst := A src, or P A P src with the coarse projector (counted)
      void
      outer_hessian(VectorType &dst, const VectorType &src);

      /// dst := (A + rho B'B) src, A as in outer_hessian()
      void
      inner_hessian(VectorType &dst, const VectorType &src);

      /// the inner problem's free-set preconditioner: the problem's M ~
      /// A^-1, with the projector P M P + B'B / rho
      std::function<std::function<void(VectorType &, const VectorType &)>(
        const VectorType &)>
      inner_preconditioner();

      const Problem<VectorType>             &problem;
      const EqualityConstraints<VectorType> &eq;
      const bool                             coarse_projector;
      const double                           rho;
      SolverStatistics                      &stats;

      /// the outer problem's linear term: b or P(b - A x0)
      VectorType b;
      VectorType lambda;
      // multiplier-sized work vectors
      VectorType Bx, residual, mu, BPv;
      // unknown-sized work vectors
      VectorType Ax, BtBx, work, g, Pv, projected_src;
    };
  } // namespace qp
} // namespace dualcontact

#endif
