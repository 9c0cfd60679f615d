#pragma once

#include <deal.II/lac/full_matrix.h>

#include <contact/contact_discretization.h>
#include <contact/contact_rows.h>
#include <contact/dual_operator.h>
#include <fem/elastic_body.h>
#include <fem/stiffness_solver.h>

#include <string>
#include <utility>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * F = B K^# B' as a dense m x m matrix (lib/contact/README.md, "The
     * dual operator: assembled from Schur factors"): F = sum_b W_b'W_b with
     * W_b = L_b^{-1} (B_b)_C', L_b the Cholesky factor of the Schur
     * complement of K_b on the dofs C_b that B touches, or B_C S_b^{-1} B_C'
     * with S_b^{-1} from L_b (dpotri) where that takes fewer flops.  A
     * product is one dsymv (m^2 flops, one triangle read).  Distributed: the
     * multipliers are gathered (one MPI_Allreduce of the m multipliers) and
     * each process multiplies by its rows of F (runs of consecutive rows, m_p x
     * m flops).
     */
    template <int dim>
    class AssembledDualOperator : public DualOperator<dim>
    {
    public:
      using typename DualOperator<dim>::VectorType;
      using typename DualOperator<dim>::DistributedVector;

      /**
       * Assembles F from the bodies' Schur factors @p schur (each body's
       * L is released once used) and, per body, the rows of B that touch
       * it (@p body_rows, ascending).
       */
      AssembledDualOperator(
        const std::vector<const fem::ElasticBody<dim> *> &bodies,
        const ContactDiscretization<dim>                 &contact,
        const ContactRows<dim>                           &rows,
        std::vector<fem::StiffnessSolver::SchurFactor>   &schur,
        const std::vector<std::vector<unsigned int>>     &body_rows);

      /**
       * F(rows, rows) -= X G + G'X' (@p X: |rows| x k, @p G: k x |rows|),
       * the rank-2k terms that make a floating body's B K^# B' its
       * B K^+ B' (DualProblem).
       */
      void
      subtract_symmetric_update(const std::vector<unsigned int>  &rows,
                                const dealii::FullMatrix<double> &X,
                                const dealii::FullMatrix<double> &G);

      void
      vmult(VectorType &dst, const VectorType &src) const override;
      void
      vmult(DistributedVector            &dst,
            const DistributedVector      &src,
            const MultiplierDistribution &owners) const override;
      bool
      is_assembled() const override;
      /** "assembled (m x m dense; Schur complements of size ...)" */
      const std::string &
      description() const override;
      double
      assembly_time() const override;

    private:
      /**
       * F_b (lower triangle, r x r column-major) = W'W, W = L^{-1} B_C'
       * (dtrtrs, dsyrk): c^2 r / 2 + c r^2 / 2 multiply-adds.
       */
      static void
      triangular_solve_route(
        const unsigned int                                               body,
        const int                                                        c,
        const std::vector<std::vector<std::pair<unsigned int, double>>> &B_C,
        const std::vector<double>                                       &lower,
        std::vector<double>                                             &Fb);
      /**
       * F_b (lower triangle) = B_C S^{-1} B_C' with S^{-1} = L^{-T} L^{-1}
       * formed in place of @p lower (dpotri, c^3 / 3 multiply-adds) and
       * two sparse products with B_C (given by rows: the positions in C
       * and values of each row's entries).
       */
      static void
      inverse_route(
        const unsigned int                                               body,
        const int                                                        c,
        const std::vector<std::vector<std::pair<unsigned int, double>>> &B_C,
        std::vector<double>                                             &lower,
        std::vector<double>                                             &Fb);

      unsigned int m_ = 0;
      /** F, m x m column-major. */
      std::vector<double> F_dense_;
      std::string         description_;
      double              assembly_time_ = 0;
      /** The gathered multipliers of a distributed product. */
      mutable dealii::Vector<double> work_lambda_;
    };
  } // namespace contact
} // namespace dualcontact
