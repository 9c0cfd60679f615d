#pragma once

#include <deal.II/lac/sparse_matrix.h>

#include <fem/stiffness_solver.h>

#include <memory>
#include <vector>

namespace dualcontact
{
  namespace fem
  {
    /**
     * A generalized inverse K^# (K K^# K = K) of a symmetric positive
     * semidefinite stiffness matrix, by the fixing-dof method: the rows and
     * columns of a few dofs that carry the kernel (RigidBodyModes::
     * fixing_dofs()) are removed, the rest K_rr is factorized by any
     * StiffnessSolver, and K^# = diag(K_rr^{-1}, 0).
     *
     * This keeps the factorization sparse and exact, unlike a
     * regularization K + rho R R' (dense) or a pseudo-inverse.  For a body
     * with enough Dirichlet conditions pass no fixing dofs: then K^# = K^{-1}.
     *
     * K^# b solves K u = b whenever b is in the range of K (b orthogonal to
     * the rigid-body modes), up to a rigid motion; the dual contact problem
     * enforces that range condition through G lambda = e.
     *
     * Given the kernel (an orthonormal basis R of the rigid-body modes),
     * solve() applies the Moore-Penrose pseudoinverse instead,
     * K^+ = (I - R R') K^# (I - R R'), at 4 n n_modes flops more.  Both
     * solve K u = b on the range of K, but K^# adds to its answers a rigid
     * motion of the size of the fixing dofs' distance, which B K^# B' then
     * carries as terms in G = R'B' that cancel only in exact arithmetic:
     * lambda_max(B K^# B') was 80 to 3.5e5 times lambda_max(B K^+ B') on
     * the brick's TFETI subdomains and 3D Hertz (doc/benchmarks/tfeti.md,
     * "Pseudoinverses").
     */
    class GeneralizedInverse : public StiffnessSolver
    {
    public:
      /**
       * K^# by @p solver on K without @p fixing_dofs; with a non-empty
       * @p kernel (orthonormal columns of R, the kernel of K) solve()
       * applies K^+.
       */
      GeneralizedInverse(
        std::unique_ptr<StiffnessSolver>                    solver,
        const std::vector<dealii::types::global_dof_index> &fixing_dofs,
        const std::vector<dealii::Vector<double>>          &kernel = {});

      void
      initialize(const dealii::SparseMatrix<double> &matrix) override;

      /** x = K^+ b with a kernel, K^# b without. */
      void
      solve(dealii::Vector<double>       &x,
            const dealii::Vector<double> &b) const override;

      /**
       * x = K^# b, also where solve() applies K^+: the assembled dual
       * operator's Schur factor is K^#'s, and the terms that make it
       * K^+'s come from K^# R (DualProblem).
       */
      void
      solve_fixing_dofs(dealii::Vector<double>       &x,
                        const dealii::Vector<double> &b) const;

      /** The kernel basis R given to the constructor (may be empty). */
      const std::vector<dealii::Vector<double>> &
      kernel() const;

      bool
      offers_schur_factor() const override;

      bool
      is_distributed() const override;

      /**
       * The Schur factor of the inner solver on @p dofs without the fixing
       * dofs (where K^# is zero): (K^#)_CC = L^{-T} L^{-1} on the kept dofs.
       */
      void
      initialize_with_schur_factor(
        const dealii::SparseMatrix<double>                 &matrix,
        const std::vector<dealii::types::global_dof_index> &dofs,
        SchurFactor                                        &schur) override;

      std::string
      name() const override;

    private:
      /** Factorize K_rr (and its Schur factor on @p schur_dofs if given). */
      void
      initialize_reduced(
        const dealii::SparseMatrix<double>                 &matrix,
        const std::vector<dealii::types::global_dof_index> *schur_dofs,
        SchurFactor                                        *schur);

      /** v -= R R'v (nothing without a kernel). */
      void
      remove_kernel(dealii::Vector<double> &v) const;

      std::unique_ptr<StiffnessSolver>             solver_;
      std::vector<dealii::types::global_dof_index> fixing_dofs_;
      std::vector<dealii::Vector<double>>          kernel_;
      /** Scratch: b with the fixing dofs zeroed, and b - R R'b. */
      mutable dealii::Vector<double> rhs_, range_part_;
    };
  } // namespace fem
} // namespace dualcontact
