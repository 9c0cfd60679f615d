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
     */
    class GeneralizedInverse : public StiffnessSolver
    {
    public:
      GeneralizedInverse(
        std::unique_ptr<StiffnessSolver>                    solver,
        const std::vector<dealii::types::global_dof_index> &fixing_dofs);

      void
      initialize(const dealii::SparseMatrix<double> &matrix) override;

      void
      solve(dealii::Vector<double>       &x,
            const dealii::Vector<double> &b) const override;

      bool
      offers_schur_factor() const override;

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

      std::unique_ptr<StiffnessSolver>             solver_;
      std::vector<dealii::types::global_dof_index> fixing_dofs_;
      mutable dealii::Vector<double>               rhs_;
    };
  } // namespace fem
} // namespace dualcontact
