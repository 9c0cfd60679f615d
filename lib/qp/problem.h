/**
 * @file problem.h
 * The QP:  minimize 1/2 x'Ax - b'x  subject to  x in Omega (separable),
 * optionally B x = c.  The Hessian is an operator, never a matrix, because
 * in the dual contact problem A = B K^+ B' is only available as products.
 */
#ifndef dualcontact_qp_problem_h
#define dualcontact_qp_problem_h

#include <qp/separable_set.h>

#include <functional>
#include <memory>

namespace dualcontact
{
  namespace qp
  {
    /**
     * Optional linear equality constraints B x = c, B of size m x n, given
     * by products (SMALSE-M needs nothing else).  Multiplier-space vectors
     * (size m) have the layout of @p c.
     */
    template <typename VectorType>
    struct EqualityConstraints
    {
      /// dst (size m) := B src (size n)
      std::function<void(VectorType &dst, const VectorType &src)> vmult;
      /// dst (size n) := B' src (size m)
      std::function<void(VectorType &dst, const VectorType &src)> Tvmult;
      /// right-hand side, also the layout of multiplier vectors
      VectorType c;
      /// m, the number of equality constraints (global)
      dealii::types::global_dof_index n_constraints = 0;
      /// ||B||^2 if known (0 = unknown), for the SMALSE-M penalty
      double norm_sq = 0.;
    };

    /**
     * Description of a QP.  Solvers count every call of `hessian`, so
     * nothing else should call it during a solve.
     */
    template <typename VectorType>
    struct Problem
    {
      /// dst := A src; A symmetric positive (semi)definite
      std::function<void(VectorType &dst, const VectorType &src)> hessian;
      /// linear term b (also the layout of x)
      VectorType b;
      /// diag(A), optional (empty vector = not given): preconditioners,
      /// scaling
      std::shared_ptr<const VectorType> diagonal;
      /// Omega; null means no inequality constraints (all unknowns free).
      /// Must be finalized for the layout of b.
      std::shared_ptr<const SeparableSet<VectorType>> constraints;
      /// B x = c, optional (null = none)
      std::shared_ptr<const EqualityConstraints<VectorType>> equality;
      /// largest eigenvalue of A if known (0 = estimate by power
      /// iteration when a step length needs it).  An upper bound is fine.
      double lambda_max = 0.;
      /// z := M_F^{-1} r, a preconditioner of the free-set block A_FF
      /// (see free_set_preconditioner)
      using FreeSetPreconditioner =
        std::function<void(VectorType &dst, const VectorType &src)>;
      /**
       * Optional factory of the preconditioner in face (MPRGP with
       * `Preconditioner = amg`, Dostal 2009, sec. 5.10): given the active
       * mask (1 on active unknowns, 0 elsewhere; layout of b) it returns
       * an operator M_F^{-1} approximating the inverse of A_FF, the block
       * of A on the free unknowns.  The solver calls it again whenever the
       * active set changed, and zeroes the active entries of the result
       * itself, so M_F^{-1} may act on all unknowns; it must be symmetric
       * positive definite on the free ones.  Whoever holds A as a matrix
       * builds it (qpsolve: FreeSetAMG); the library stays matrix-free.
       */
      std::function<FreeSetPreconditioner(const VectorType &active_mask)>
        free_set_preconditioner;
      /// hint: A may be singular (SPS).  Informational: MPRGP runs the
      /// solvability test of MPRGPS (thesis 2.4.5) in any case.
      bool semidefinite = false;
    };
  } // namespace qp
} // namespace dualcontact

#endif
