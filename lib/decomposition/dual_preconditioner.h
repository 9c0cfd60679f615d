#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <decomposition/constraint_rows.h>
#include <decomposition/interface_schur_complement.h>
#include <decomposition/multiplier_scaling.h>
#include <decomposition/subdomain.h>
#include <fem/stiffness_solver.h>

#include <functional>
#include <memory>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * TFETI's dual preconditioners, scaled (Rixen and Farhat 1999):
     *
     *   M^{-1} = Q B A B' Q,  Q = (B B')^{-1},  A = diag(A_s),
     *
     * A_s = K_s (lumped: sparse products with the subdomains' stiffness
     * matrices) or S_s (Dirichlet: the Schur complement of K_s onto the
     * dofs its rows of B touch, InterfaceSchurComplement).  For the
     * non-redundant gluing rows B A B' alone misses F^{-1} by the square of
     * the chain's matrix at a dof shared by k subdomains (condition number
     * 34 at k = 4, 640 at k = 8); Q makes the two exact at such a dof.
     * B B' is sparse (rows meet only at shared dofs) and factorized once
     * (MultiplierScaling), from the (row, row, value) triples of every
     * process' subdomains.
     *
     * The products with B and B' are TFETIDual's (the callback given to
     * the constructor: B' to the owned subdomains, A_s there, B back and
     * summed over the processes); this class holds what is particular to
     * the preconditioner.  Collective: construction and vmult().
     */
    template <int dim>
    class DualPreconditioner
    {
    public:
      using VectorType = dealii::Vector<double>;
      /** y = A_s v for subdomain s, in its local numbering (y sized and
       *  zeroed). */
      using LocalOperator =
        std::function<void(unsigned int, VectorType &, const VectorType &)>;
      /** dst = sum_s B_s A_s B_s' src over every process' subdomains. */
      using BetweenB = std::function<
        void(VectorType &, const VectorType &, const LocalOperator &)>;

      enum class Kind
      {
        lumped,
        dirichlet
      };

      /**
       * Builds Q (and, for Kind::dirichlet, the Schur complements of the
       * @p owned subdomains, factorized by the solvers @p make_solver
       * returns).  @p subdomains must keep their stiffness matrices.
       */
      DualPreconditioner(
        const Kind                                          kind,
        const ConstraintRows<dim>                          &rows,
        const std::vector<std::unique_ptr<Subdomain<dim>>> &subdomains,
        const std::vector<unsigned int>                    &owned,
        const unsigned int                                  n_multipliers,
        const MPI_Comm                                      communicator,
        const std::function<std::unique_ptr<fem::StiffnessSolver>()>
                &make_solver,
        BetweenB between_B);

      /** dst = Q B A B' Q src (collective). */
      void
      vmult(VectorType &dst, const VectorType &src) const;

      Kind
      kind() const;

    private:
      /** Q = (B B')^{-1} from the entries of the owned subdomains' rows,
       *  gathered from every process. */
      void
      build_scaling(const unsigned int n_multipliers,
                    const MPI_Comm     communicator);
      /** The InterfaceSchurComplement of every owned subdomain. */
      void
      build_schur_complements(
        const std::function<std::unique_ptr<fem::StiffnessSolver>()>
          &make_solver);

      Kind                                                kind_;
      const ConstraintRows<dim>                          &rows_;
      const std::vector<std::unique_ptr<Subdomain<dim>>> &subdomains_;
      const std::vector<unsigned int>                    &owned_;
      BetweenB                                            between_B_;
      std::unique_ptr<MultiplierScaling>                  scaling_;
      /** Per subdomain (owned ones only; empty for Kind::lumped). */
      std::vector<std::unique_ptr<InterfaceSchurComplement>> schur_;
    };
  } // namespace decomposition
} // namespace dualcontact
