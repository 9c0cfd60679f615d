#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <string>

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

      virtual ~StiffnessSolver() = default;

      /** Analyse and factorize @p matrix (kept by reference where needed). */
      virtual void
      initialize(const dealii::SparseMatrix<double> &matrix) = 0;

      /** x = K^{-1} b. */
      virtual void
      solve(dealii::Vector<double>       &x,
            const dealii::Vector<double> &b) const = 0;

      /** A short name, e.g. "cholmod". */
      virtual std::string
      name() const = 0;

      const Statistics &
      statistics() const;

      /** Declare the subsection `Stiffness solver` in @p prm. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Create the solver chosen in the subsection `Stiffness solver`. */
      static std::unique_ptr<StiffnessSolver>
      create(dealii::ParameterHandler &prm);

    protected:
      mutable Statistics statistics_;
    };
  } // namespace fem
} // namespace dualcontact
