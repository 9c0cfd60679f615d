#pragma once

#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <fem/elastic_body.h>
#include <fem/rigid_body_modes.h>
#include <fem/stiffness_solver.h>

#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * One subdomain of a body in TFETI: a set of the body's active cells
     * with its own copy of their dofs (numbered locally: local dof i is the
     * body dof dofs()[i], sorted), its stiffness matrix K_s and load f_s
     * assembled from these cells alone without any constraint (Dirichlet
     * conditions and hanging nodes are multiplier rows in TFETI, so every
     * subdomain floats),
     * its kernel R_s (the dim (dim + 1) / 2 rigid-body motions,
     * orthonormal), and its generalized inverse K_s^# (the fixing-dof
     * method around the given stiffness solver).
     */
    template <int dim>
    class Subdomain
    {
    public:
      using CellIterator =
        typename dealii::DoFHandler<dim>::active_cell_iterator;

      /**
       * Assembles K_s and f_s of @p cells of @p body and finds R_s
       * (@p support_points and @p components: the body's, per dof).
       */
      Subdomain(const fem::ElasticBody<dim>           &body,
                const unsigned int                     body_index,
                const std::vector<CellIterator>       &cells,
                const std::vector<dealii::Point<dim>> &support_points,
                const std::vector<unsigned int>       &components,
                const std::string                     &name);

      /**
       * f_s again from the body's loads at their current time
       * (fem::ElasticBody::set_load_time()): a load step.  K_s and its
       * factorization stay.
       */
      void
      assemble_load();

      /**
       * Factorizes K_s with @p solver inside a fem::GeneralizedInverse on
       * the fixing dofs of R_s.
       */
      void
      factorize(std::unique_ptr<fem::StiffnessSolver> solver);

      /**
       * Frees K_s (its factor stays): for a solve without a preconditioner
       * that applies K_s, about a third of a subdomain's memory.  Then
       * stiffness_matrix() may not be called.
       */
      void
      release_stiffness_matrix();

      /**
       * x = K_s^+ b (local numbering), the Moore-Penrose pseudoinverse:
       * (I - R R') K_s^# (I - R R') b with the fixing-dof generalized
       * inverse K_s^# and the orthonormal modes R = R_s
       * (fem::GeneralizedInverse given the kernel).  Any generalized
       * inverse gives TFETI the same P F P, but F, d and the projected
       * linear term differ by terms in G that cancel only in exact
       * arithmetic, and K^# can be larger than K^+ by orders of magnitude
       * where the fixing nodes hold the subdomain weakly (3D Hertz cut
       * into 35 subdomains, some of one refined cell: lambda_max(B K^# B')
       * 2.5e7 m/N against lambda_max(P F P) 69 m/N, and the inner QPs lost
       * every digit below 1e-10 to the cancellation).  The two projections
       * cost 4 n_modes n_dofs flops, against the solve's 4 nnz(L).
       */
      void
      apply_pseudoinverse(dealii::Vector<double>       &x,
                          const dealii::Vector<double> &b) const;

      /** The local index of body dof @p dof (which must be one of dofs()). */
      unsigned int
      local_index(const dealii::types::global_dof_index dof) const;

      const std::string &
      name() const;
      unsigned int
      body() const;
      unsigned int
      n_cells() const;
      unsigned int
      n_dofs() const;
      const std::vector<dealii::types::global_dof_index> &
      dofs() const;
      const dealii::Vector<double> &
      load() const;
      const dealii::SparseMatrix<double> &
      stiffness_matrix() const;
      /** The orthonormal columns of R_s (local numbering). */
      const std::vector<dealii::Vector<double>> &
      modes() const;
      const fem::StiffnessSolver &
      solver() const;

    private:
      std::string                  name_;
      const fem::ElasticBody<dim> *body_object_;
      unsigned int                 body_;
      /** The cells of the subdomain (on this process). */
      std::vector<CellIterator>                    cells_;
      unsigned int                                 n_cells_;
      std::vector<dealii::types::global_dof_index> dofs_;
      dealii::SparsityPattern                      sparsity_;
      dealii::SparseMatrix<double>                 stiffness_;
      dealii::Vector<double>                       load_;
      std::unique_ptr<fem::RigidBodyModes<dim>>    modes_;
      /** K_s^+: a fem::GeneralizedInverse given R_s. */
      std::unique_ptr<fem::StiffnessSolver> solver_;
    };
  } // namespace decomposition
} // namespace dualcontact
