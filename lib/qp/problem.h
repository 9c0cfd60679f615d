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
#include <vector>

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
      /// B B' = I (the rows orthonormal, as TFETI's G~ = L^-1 G with
      /// G G' = L L'): SMALSE-M may then work with the projector
      /// P = I - B'B onto the kernel of B (SMALSEMParameters::
      /// coarse_projector)
      bool orthonormal_rows = false;
      /// rho / lambda_max(A) of SMALSE-M's coarse projector when its
      /// `Projector penalty factor' is automatic: the formulation's
      /// measured choice (TFETI 3 or 1, the undecomposed dual 10 or 1)
      double projector_penalty_factor = 1.;
      /// lambda_max(P A P) with P = I - B'B (orthonormal rows only) if
      /// known (0 = unknown): SMALSE-M's coarse projector then sets rho
      /// and the inner step lengths from it instead of lambda_max(A),
      /// which a generalized inverse in A can make larger by orders of
      /// magnitude without changing P A P (TFETI)
      double projected_lambda_max = 0.;
    };

    /**
     * Description of a QP.  Solvers count every call of `hessian`, so
     * nothing else should call it during a solve.
     */
    /**
     * What the Hessian is, as far as `Solver = auto` cares when it
     * chooses the settings of its solvers (SolverChain::
     * attempt_parameters): an assembled sparse matrix whose
     * Problem::free_set_preconditioner is an AMG of it (qpsolve: the
     * membrane of benchmark B4, where MPRGP with the AMG in face is 4 to
     * 20 times faster than without), a dense matrix (the contact dual F,
     * FCLIB's Delassus W: products cost O(n^2), no multigrid), or an
     * operator of unknown form (the default; auto then uses the given
     * parameters).
     */
    enum class HessianStorage
    {
      operator_only,
      sparse_matrix,
      dense_matrix
    };

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
      /// hint for `Solver = auto` (HessianStorage): who builds A as a
      /// sparse matrix and supplies free_set_preconditioner sets
      /// sparse_matrix
      HessianStorage hessian_storage = HessianStorage::operator_only;
      /**
       * Optional: A x0 - b at the start x0 that is passed to solve().
       * Loops that solve QPs with the same A and b one after another, each
       * from the last one's solution, where only the set changes (the
       * Coulomb fixed point over Tresca QPs), pass the gradient the previous
       * solve ended with (SolverBase::final_gradient()): the active-set
       * solvers then skip their first product when the start is feasible
       * for the new set (the projection leaves it unchanged), which on a
       * small contact problem is a tenth of the loop's products.  The
       * caller vouches that it is A x0 - b; the other solvers ignore it.
       */
      std::shared_ptr<const VectorType> start_gradient;
      /**
       * Optional, with start_gradient: dst += A d for a d that is zero
       * outside the given local indices, at a cost proportional to their
       * number (e.g. the columns of a dense A).  When the projection onto
       * the new set moves a few unknowns of the start (a few contacts of a
       * Coulomb loop change between sticking and sliding), the active-set
       * solvers correct start_gradient with it instead of a product.
       */
      std::function<void(VectorType                     &dst,
                         const VectorType               &d,
                         const std::vector<std::size_t> &indices)>
        hessian_add_sparse;
    };
  } // namespace qp
} // namespace dualcontact

#endif
