#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace fem
  {
    /**
     * Applies K^{-1} (later K^+, a generalized inverse, for floating bodies)
     * to vectors: the one operation the dual contact problem needs from the
     * primal side.  A factorization is done once in initialize() and reused
     * by every solve(), since the dual solvers apply K^{-1} hundreds of
     * times.
     *
     * Implementations are chosen by name in the parameter subsection
     * `Stiffness solver` (see declare_parameters()).
     */
    class StiffnessSolver
    {
    public:
      /** Figures of the last initialize()/solve() calls, for the statistics. */
      struct Statistics
      {
        double       setup_time      = 0; ///< analysis + factorization [s]
        double       solve_time      = 0; ///< all solves together [s]
        unsigned int n_solves        = 0;
        double       factor_nonzeros = 0; ///< nnz of the factor (direct)
        double       factor_flops    = 0; ///< flops of the factorization
        unsigned int iterations      = 0; ///< last solve (iterative solvers)
      };

      /**
       * The Cholesky factor of the Schur complement of K onto a few dofs C
       * (the dofs the contact matrices touch):
       *   S = K_CC - K_CI K_II^{-1} K_IC = L L',   so   (K^{-1})_CC = L^{-T}
       * L^{-1}. The dual operator F = B K^{-1} B' only ever reads the block
       * (K^{-1})_CC, so with L it can be assembled as a dense matrix
       * W'W, W = L^{-1} B_C', and a Hessian product of the dual QP costs
       * m^2 flops (m multipliers) instead of a forward and a backward
       * substitution with the whole factor.  A direct solver gets L for free
       * by ordering C last: L is then the trailing block of its factor.
       */
      struct SchurFactor
      {
        /**
         * The dofs (indices of the matrix given to initialize()) that the
         * rows and columns of L stand for, in order.  For a generalized
         * inverse the fixing dofs are left out: K^# is zero there.
         */
        std::vector<dealii::types::global_dof_index> dofs;
        /** L, lower triangular, dofs.size() x dofs.size(), column-major. */
        std::vector<double> lower;
      };

      virtual ~StiffnessSolver() = default;

      /** Analyse and factorize @p matrix (every implementation keeps its
       *  own copy or factor: @p matrix need not outlive this call). */
      virtual void
      initialize(const dealii::SparseMatrix<double> &matrix) = 0;

      /** x = K^{-1} b. */
      virtual void
      solve(dealii::Vector<double>       &x,
            const dealii::Vector<double> &b) const = 0;

      /** Whether initialize_with_schur_factor() is offered. */
      virtual bool
      offers_schur_factor() const;

      /**
       * Whether the factor is spread over the processes (MUMPS, AMG through
       * Trilinos: solve() is collective).  A serial solver (CHOLMOD,
       * UMFPACK) under MPI factorizes the whole matrix on every process,
       * and every process solves on its own.
       */
      virtual bool
      is_distributed() const;

      /**
       * Like initialize(), and also compute the SchurFactor onto @p dofs
       * (distinct indices; their order is kept).  solve() works as after
       * initialize().  Throws unless offers_schur_factor().
       */
      virtual void
      initialize_with_schur_factor(
        const dealii::SparseMatrix<double>                 &matrix,
        const std::vector<dealii::types::global_dof_index> &dofs,
        SchurFactor                                        &schur);

      /** A short name, e.g. "cholmod". */
      virtual std::string
      name() const = 0;

      const Statistics &
      statistics() const;

      /** Declare the subsection `Stiffness solver` in @p prm. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /**
       * Gives OpenBLAS the threads `BLAS threads` asks for (automatic:
       * util::automatic_blas_threads()) and says what it did for the log,
       * e.g. "2 (automatic: load average 0.12 on 2 cores)".  Throws,
       * naming the parameter, on a value that is neither `automatic' nor
       * a whole number >= 1.
       */
      static std::string
      apply_blas_threads(dealii::ParameterHandler &prm);

      /** Create the solver chosen in the subsection `Stiffness solver`. */
      static std::unique_ptr<StiffnessSolver>
      create(dealii::ParameterHandler &prm);

      /** Create the solver @p solver (a name of `Solver' other than
       *  automatic) with the other settings of `Stiffness solver'. */
      static std::unique_ptr<StiffnessSolver>
      create(dealii::ParameterHandler &prm, const std::string &solver);

      /**
       * The solver `Solver = @p name' stands for: `automatic' is cholmod on
       * any number of processes (under MPI every process factorizes the
       * whole matrix); any other name is itself.
       */
      static std::string
      resolved_name(const std::string &name);

      /**
       * Whether the solver named @p solver (a resolved name) spreads its
       * factor over the processes (mumps, amg; its is_distributed() is
       * true); cholmod and umfpack hold the whole factor on every process.
       */
      static bool
      spreads_over_processes(const std::string &solver);

      /**
       * Where to tell about a long setup while it runs: a sparse
       * factorization cannot report its progress, so a direct solver calls
       * @p monitor before it (matrix order, factor size, flops and an
       * estimate of the time) and after it (the time taken).  Unset: quiet.
       */
      void
      set_monitor(std::function<void(const std::string &)> monitor);

    protected:
      mutable Statistics                       statistics_;
      std::function<void(const std::string &)> monitor_;
    };
  } // namespace fem
} // namespace dualcontact
