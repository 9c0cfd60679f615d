/**
 * @file free_set_amg.h
 * The algebraic multigrid preconditioner in face for a QP whose Hessian is
 * an explicit sparse matrix (qpsolve): the Problem::free_set_preconditioner
 * factory that builds Trilinos ML (dealii::TrilinosWrappers::
 * PreconditionAMG) on A with the rows and columns of the active unknowns
 * replaced by identity rows, i.e. on A_FF with decoupled unit rows beside
 * it.  Why not A itself: on the membrane the contact zone is a third of
 * the unknowns, and an AMG of A approximates A^{-1}, whose free-set block
 * is not (A_FF)^{-1}; the restricted matrix gives PCG on A_FF exactly the
 * multigrid quality that makes the iteration count independent of the
 * mesh (Dostal 2009, sec. 5.10).
 */
#ifndef dualcontact_qp_free_set_amg_h
#define dualcontact_qp_free_set_amg_h

#include <qp/problem.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

namespace dualcontact
{
  namespace qp
  {
    /**
     * Factory of AMG preconditioners of A_FF for the free sets MPRGP meets
     * (`Preconditioner = amg`).  Holds a reference to A (which must outlive
     * it and every operator it returned) and one work matrix of A's
     * sparsity.  Serial (dealii::Vector<double>), like qpsolve.
     */
    class FreeSetAMG
    {
    public:
      using Vec = dealii::Vector<double>;

      /// AMG parameters; the defaults are deal.II's for an elliptic
      /// scalar problem (one V-cycle, Chebyshev smoother with 2 sweeps,
      /// which keeps the preconditioner symmetric as PCG needs).
      struct Parameters
      {
        /// ML aggregation threshold (deal.II default 1e-4)
        double aggregation_threshold = 1e-4;
        /// smoother sweeps per level (deal.II default 2)
        unsigned int smoother_sweeps = 2;
        /// V-cycles per application (deal.II default 1)
        unsigned int n_cycles = 1;
      };

      /// with the default Parameters
      explicit FreeSetAMG(const dealii::SparseMatrix<double> &A);
      FreeSetAMG(const dealii::SparseMatrix<double> &A,
                 const Parameters                   &parameters);

      /**
       * Build the AMG of A_FF for the free set given by @p active_mask
       * (1 on active unknowns) and return it as M_F^{-1}.  The operator
       * keeps its AMG alive; the solver drops it at the next rebuild.
       */
      typename Problem<Vec>::FreeSetPreconditioner
      build(const Vec &active_mask);

      /// build() as the factory Problem::free_set_preconditioner wants
      /// (captures this object, which must outlive the solve)
      std::function<typename Problem<Vec>::FreeSetPreconditioner(const Vec &)>
      factory();

    private:
      const dealii::SparseMatrix<double> &matrix;
      const Parameters                    parameters;
      /// A with the active rows and columns replaced by identity rows
      dealii::SparseMatrix<double> restricted;
      /// the value of those identity rows: the mean of diag(A), so that
      /// they do not change the scale ML sees
      double unit = 1.;
    };
  } // namespace qp
} // namespace dualcontact

#endif
