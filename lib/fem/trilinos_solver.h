#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fem/stiffness_solver.h>

#include <memory>
#include <string>

namespace dualcontact
{
  namespace fem
  {
    /**
     * K^{-1} on a Trilinos distributed matrix, for runs under MPI (and on one
     * process, as a check): MUMPS through Trilinos Amesos (`Amesos_Mumps',
     * a distributed multifrontal LU, factorized once and reused by every
     * solve), or conjugate gradients preconditioned by Trilinos ML algebraic
     * multigrid (no factorization: every solve iterates to a relative
     * residual, so K^{-1} is applied only approximately and the dual
     * operator is symmetric only to that tolerance).
     *
     * Rows are distributed in contiguous ranges, one per process: the range
     * given by set_locally_owned_rows() (a DoFHandler's locally owned dofs on
     * a parallel::shared::Triangulation, whose METIS subdomains are numbered
     * contiguously), or an even split of the rows.  The StiffnessSolver
     * interface takes the whole (replicated) matrix and vectors on every
     * process and returns the whole solution on every process: each process
     * copies its rows into the distributed matrix, and the distributed
     * solution is gathered (one MPI_Allgatherv per solve).  The distributed
     * interface (initialize/solve on Trilinos objects) skips both copies.
     */
    class TrilinosSolver : public StiffnessSolver
    {
    public:
      enum class Method
      {
        /** LU by MUMPS (Trilinos Amesos). */
        mumps,
        /** CG preconditioned by ML algebraic multigrid. */
        amg_cg
      };

      /** Parameters (subsection `Stiffness solver'). */
      struct Parameters
      {
        Method method = Method::mumps;
        /** CG stops when ||K x - b|| <= tolerance ||b|| [-]. */
        double cg_tolerance = 1e-12;
        /** CG iteration limit; reaching it is an error. */
        unsigned int cg_max_iterations = 10000;
        /** ML aggregation threshold [-]. */
        double aggregation_threshold = 1e-4;
        /** ML smoother sweeps (Chebyshev). */
        unsigned int smoother_sweeps = 2;
      };

      explicit TrilinosSolver(const Parameters &parameters,
                              const MPI_Comm    communicator = MPI_COMM_WORLD);
      ~TrilinosSolver() override;

      /**
       * The rows this process owns in the next initialize() from a deal.II
       * matrix (a contiguous range; together the processes own all rows).
       * Ignored if its size differs from the matrix's.
       */
      void
      set_locally_owned_rows(const dealii::IndexSet &rows);

      /**
       * Unknowns per mesh node, numbered consecutively (dim for the
       * displacements of an ElasticBody): ML then aggregates whole nodes
       * with the translations as near null space.  Default 1 (scalar
       * aggregation).  Used when the number of rows is a multiple.
       */
      void
      set_block_size(const unsigned int block_size);

      /** Copy this process's rows of @p matrix, then as the next one. */
      void
      initialize(const dealii::SparseMatrix<double> &matrix) override;

      /** Factorize (MUMPS) or build the AMG hierarchy of @p matrix. */
      void
      initialize(const dealii::TrilinosWrappers::SparseMatrix &matrix);

      /** x = K^{-1} b, both whole vectors on every process. */
      void
      solve(dealii::Vector<double>       &x,
            const dealii::Vector<double> &b) const override;

      /** x = K^{-1} b, distributed like the matrix's rows. */
      void
      solve(dealii::TrilinosWrappers::MPI::Vector       &x,
            const dealii::TrilinosWrappers::MPI::Vector &b) const;

      /** "mumps" or "amg". */
      std::string
      name() const override;

      /** True: the factor (or hierarchy) is spread over the processes. */
      bool
      is_distributed() const override;

      /** The rows of this process (after initialize()). */
      const dealii::IndexSet &
      locally_owned_rows() const;

    private:
      void
      setup(const dealii::TrilinosWrappers::SparseMatrix &matrix);

      const Parameters parameters_;
      const MPI_Comm   communicator_;
      unsigned int     block_size_ = 1;
      dealii::IndexSet requested_rows_;
      dealii::IndexSet owned_rows_;
      /** First row and number of rows of every process (for the gather). */
      std::vector<int> offsets_, counts_;

      /** The matrix copied from a deal.II one (else the caller's). */
      dealii::TrilinosWrappers::SparseMatrix        own_matrix_;
      const dealii::TrilinosWrappers::SparseMatrix *matrix_ = nullptr;
      mutable dealii::SolverControl                 direct_control_;
      mutable std::unique_ptr<dealii::TrilinosWrappers::SolverDirect> direct_;
      std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG>      amg_;
      mutable dealii::TrilinosWrappers::MPI::Vector work_x_, work_b_;
    };
  } // namespace fem
} // namespace dualcontact
