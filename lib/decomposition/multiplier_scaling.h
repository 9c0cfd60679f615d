#pragma once

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <fem/stiffness_solver.h>

#include <memory>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * The scaling Q = (B B')^{-1} of TFETI's lumped and Dirichlet
     * preconditioners, Q B K B' Q and Q B S B' Q (Rixen and Farhat's
     * "superlumped" scaling, doc/benchmarks/tfeti.md): without it a dof
     * shared by k subdomains enters the preconditioned operator with the
     * factor k^2 and the preconditioners cost iterations.  B B' is sparse
     * (rows couple only where they share a dof), assembled once from the
     * products of the rows' entries and factorized by CHOLMOD.
     */
    class MultiplierScaling
    {
    public:
      /**
       * B B' for @p n_rows rows from @p products: (row i, row j, b_i b_j)
       * triples, one per pair of entries of a column of B, over all the
       * processes' subdomains.  A zero row of B (a contact node whose dofs
       * are all under Dirichlet conditions) couples to nothing: Q is the
       * identity there.  Throws if B B' is singular (dependent rows).
       */
      MultiplierScaling(const unsigned int         n_rows,
                        const std::vector<double> &products);

      /// v := (B B')^{-1} v
      void
      apply(dealii::Vector<double> &v) const;

    private:
      dealii::SparsityPattern                       sparsity;
      dealii::SparseMatrix<double>                  bbt;
      mutable std::unique_ptr<fem::StiffnessSolver> factor;
      mutable dealii::Vector<double>                scaled;
    };
  } // namespace decomposition
} // namespace dualcontact
