#pragma once

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <fem/stiffness_solver.h>

#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * The Schur complement of a subdomain's stiffness matrix onto its
     * interface dofs b (every dof that a row of B touches: gluing,
     * Dirichlet and contact dofs),
     *
     *   S = K_bb - K_bi K_ii^{-1} K_ib,
     *
     * applied without forming it: for v on b, the interior values
     * x_i = -K_ii^{-1} K_ib v_b make x = [v_b; x_i] the discrete harmonic
     * extension of v_b, and (K x)_b = S v_b.  That is one solve with the
     * factor of K_ii (the subdomain with its interface clamped: positive
     * definite once b holds three non-collinear nodes, dim = 3) and two
     * sparse products with K.  It is the subdomain's share of TFETI's
     * Dirichlet preconditioner sum_s B_s S_s B_s' (Farhat, Mandel, Roux
     * 1994; thesis 3.1 names the lumped and the Dirichlet one).
     */
    class InterfaceSchurComplement
    {
    public:
      /**
       * Extracts K_ii of @p stiffness (the dofs not in @p interface, a
       * sorted list of local dofs) and factorizes it with @p solver.
       * @p name (the subdomain's) is in the message when K_ii is singular.
       */
      InterfaceSchurComplement(const dealii::SparseMatrix<double>   &stiffness,
                               const std::vector<unsigned int>      &interface,
                               std::unique_ptr<fem::StiffnessSolver> solver,
                               const std::string                    &name);

      /**
       * y = S v on the interface dofs, y = 0 on the interior ones; entries
       * of @p v off the interface are ignored.  Vectors of the subdomain's
       * local numbering.
       */
      void
      vmult(dealii::Vector<double> &y, const dealii::Vector<double> &v) const;

      unsigned int
      n_interface_dofs() const;
      unsigned int
      n_interior_dofs() const;
      /** The factor of K_ii, for its figures (nonzeros, times). */
      const fem::StiffnessSolver &
      solver() const;

    private:
      const dealii::SparseMatrix<double> &stiffness_;
      /** The interior dofs in local numbering, ascending. */
      std::vector<unsigned int>             interior_;
      unsigned int                          n_interface_;
      dealii::SparsityPattern               interior_sparsity_;
      dealii::SparseMatrix<double>          interior_stiffness_;
      std::unique_ptr<fem::StiffnessSolver> solver_;
      mutable dealii::Vector<double>        extension_, interior_rhs_,
        interior_solution_;
    };
  } // namespace decomposition
} // namespace dualcontact
