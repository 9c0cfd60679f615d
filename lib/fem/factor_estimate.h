#pragma once

#include <deal.II/lac/sparsity_pattern.h>

#include <fem/cholmod_solver.h>

namespace dualcontact
{
  namespace fem
  {
    /**
     * What a Cholesky factorization of a symmetric matrix with a given
     * sparsity pattern will cost, before any value is assembled: CHOLMOD's
     * symbolic analysis (the ordering, the elimination tree and the
     * column counts) of the pattern alone.  It gives the factor's nonzeros
     * and the numerical factorization's flops exactly (the values do not
     * change either), at a small fraction of the factorization's time
     * (the brick at 40 x 80 x 40, 408,483 dofs: a few seconds against
     * 5,470 GFlop).  decomposition::MethodChoice compares the undecomposed
     * factor with TFETI's subdomain factors by it.
     */
    class FactorEstimate
    {
    public:
      /** The pattern's order, the factor's nonzeros and the factorization's
       * floating-point operations. */
      struct Result
      {
        double n_rows          = 0;
        double factor_nonzeros = 0;
        double flops           = 0;
        /** The factor's size [MB]: 8 bytes a nonzero (the values; the
         * supernodal index arrays add a few per cent). */
        double
        megabytes() const
        {
          return 8e-6 * factor_nonzeros;
        }
      };

      /** The analysis of @p pattern (square; only its upper triangle is
       * read) with @p ordering as CholmodSolver would order it. */
      static Result
      analyze(const dealii::SparsityPattern &pattern,
              const CholmodSolver::Ordering  ordering);
    };
  } // namespace fem
} // namespace dualcontact
