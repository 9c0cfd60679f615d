#include <deal.II/base/exceptions.h>

#include <fem/factor_estimate.h>

#include <cholmod.h>

#include <memory>

namespace dualcontact
{
  namespace fem
  {
    namespace
    {
      /** cholmod_common, started and finished with its scope. */
      struct Common
      {
        cholmod_common c;
        Common()
        {
          cholmod_l_start(&c);
          c.print         = 0;
          c.error_handler = nullptr;
          c.supernodal    = CHOLMOD_SUPERNODAL;
        }
        ~Common()
        {
          cholmod_l_finish(&c);
        }
      };


      /** The ordering settings CholmodSolver's constructor makes. */
      void
      set_ordering(cholmod_common &c, const CholmodSolver::Ordering ordering)
      {
        using Ordering = CholmodSolver::Ordering;
        if (ordering == Ordering::automatic)
          return;
        c.nmethods           = 1;
        c.method[0].ordering = ordering == Ordering::amd   ? CHOLMOD_AMD :
                               ordering == Ordering::metis ? CHOLMOD_METIS :
                                                             CHOLMOD_NESDIS;
        c.postorder          = 1;
      }
    } // namespace


    FactorEstimate::Result
    FactorEstimate::analyze(const dealii::SparsityPattern &pattern,
                            const CholmodSolver::Ordering  ordering)
    {
      AssertThrow(pattern.n_rows() == pattern.n_cols(),
                  dealii::ExcMessage("FactorEstimate: the pattern is not "
                                     "square."));
      Common common;
      set_ordering(common.c, ordering);
      const SuiteSparse_long n = pattern.n_rows();
      // row i, entries j >= i, as column i of the lower triangle (the
      // layout CholmodSolver hands over), values left out
      std::size_t nnz = 0;
      for (SuiteSparse_long i = 0; i < n; ++i)
        for (auto it = pattern.begin(i); it != pattern.end(i); ++it)
          if (static_cast<SuiteSparse_long>(it->column()) >= i)
            ++nnz;
      cholmod_sparse *A = cholmod_l_allocate_sparse(
        n, n, nnz, 0, 1, -1, CHOLMOD_PATTERN, &common.c);
      AssertThrow(A != nullptr,
                  dealii::ExcMessage("CHOLMOD: out of memory allocating the "
                                     "pattern of order " +
                                     std::to_string(n) + "."));
      auto       *column_start = static_cast<SuiteSparse_long *>(A->p);
      auto       *row_index    = static_cast<SuiteSparse_long *>(A->i);
      std::size_t k            = 0;
      for (SuiteSparse_long i = 0; i < n; ++i)
      {
        column_start[i] = k;
        for (auto it = pattern.begin(i); it != pattern.end(i); ++it)
          if (static_cast<SuiteSparse_long>(it->column()) >= i)
            row_index[k++] = it->column();
      }
      column_start[n]        = k;
      cholmod_factor *factor = cholmod_l_analyze(A, &common.c);
      const int       status = common.c.status;
      Result          result;
      result.n_rows          = n;
      result.factor_nonzeros = common.c.lnz;
      result.flops           = common.c.fl;
      const bool analyzed    = factor != nullptr;
      if (analyzed)
        cholmod_l_free_factor(&factor, &common.c);
      cholmod_l_free_sparse(&A, &common.c);
      AssertThrow(analyzed && status >= CHOLMOD_OK,
                  dealii::ExcMessage("CHOLMOD: symbolic analysis failed "
                                     "(status " +
                                     std::to_string(status) + ")."));
      return result;
    }
  } // namespace fem
} // namespace dualcontact
