#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <fem/cholmod_solver.h>

#include <cholmod.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace dualcontact
{
  namespace fem
  {
    struct CholmodSolver::Data
    {
      cholmod_common   common;
      cholmod_factor  *factor = nullptr;
      SuiteSparse_long n      = 0;
    };


    namespace
    {
      /**
       * The rate [flop/s] of the last numerical factorization of at least
       * 10^8 flops in this process, for the estimate of the next one; before
       * the first, 10 GFlop/s (the order of a supernodal factorization with
       * OpenBLAS on one core of this project's machines).
       */
      double measured_rate = 1e10;

      std::string
      format(const char *pattern, const double value)
      {
        char text[64];
        std::snprintf(text, sizeof(text), pattern, value);
        return text;
      }
    } // namespace


    CholmodSolver::CholmodSolver(const Ordering ordering)
        : ordering_(ordering)
        , data_(std::make_unique<Data>())
    {
      cholmod_l_start(&data_->common);
      cholmod_common &c = data_->common;
      c.supernodal      = CHOLMOD_SUPERNODAL;
      c.print           = 0;
      // Errors are turned into exceptions after each call; do not let
      // CHOLMOD print them as well.
      c.error_handler = nullptr;
      switch (ordering_)
      {
        case Ordering::automatic:
          break;
        case Ordering::amd:
          c.nmethods           = 1;
          c.method[0].ordering = CHOLMOD_AMD;
          c.postorder          = 1;
          break;
        case Ordering::metis:
          c.nmethods           = 1;
          c.method[0].ordering = CHOLMOD_METIS;
          c.postorder          = 1;
          break;
        case Ordering::nested_dissection:
          c.nmethods           = 1;
          c.method[0].ordering = CHOLMOD_NESDIS;
          c.postorder          = 1;
          break;
      }
    }


    CholmodSolver::~CholmodSolver()
    {
      free_factor();
      cholmod_l_finish(&data_->common);
    }


    void
    CholmodSolver::free_factor()
    {
      if (data_->factor != nullptr)
        cholmod_l_free_factor(&data_->factor, &data_->common);
      data_->factor = nullptr;
    }


    void
    CholmodSolver::initialize(const dealii::SparseMatrix<double> &matrix)
    {
      factorize(matrix, nullptr);
    }


    void
    CholmodSolver::factorize(const dealii::SparseMatrix<double> &matrix,
                             const std::vector<long>            *permutation,
                             const bool                          numeric)
    {
      AssertThrow(matrix.m() == matrix.n(),
                  dealii::ExcMessage("CHOLMOD: the matrix is not square."));
      dealii::Timer   timer;
      cholmod_common &c = data_->common;
      free_factor();
      const SuiteSparse_long n = matrix.m();
      data_->n                 = n;

      // Row i of the symmetric CSR matrix, entries j >= i, is column i of the
      // lower triangle in CSC form (stype = -1).  Explicit zeros off the
      // diagonal are dropped: condensed constraints leave many of them.
      std::size_t nnz = 0;
      for (SuiteSparse_long i = 0; i < n; ++i)
        for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
          if (static_cast<SuiteSparse_long>(it->column()) >= i &&
              (it->value() != 0. ||
               static_cast<SuiteSparse_long>(it->column()) == i))
            ++nnz;
      cholmod_sparse *A = cholmod_l_allocate_sparse(
        n, n, nnz, /*sorted=*/0, /*packed=*/1, /*stype=*/-1, CHOLMOD_REAL, &c);
      AssertThrow(A != nullptr,
                  dealii::ExcMessage("CHOLMOD: out of memory allocating a " +
                                     std::to_string(n) + " x " +
                                     std::to_string(n) + " matrix."));
      auto       *column_start = static_cast<SuiteSparse_long *>(A->p);
      auto       *row_index    = static_cast<SuiteSparse_long *>(A->i);
      auto       *values       = static_cast<double *>(A->x);
      std::size_t k            = 0;
      for (SuiteSparse_long i = 0; i < n; ++i)
      {
        column_start[i] = k;
        for (auto it = matrix.begin(i); it != matrix.end(i); ++it)
        {
          const auto j = static_cast<SuiteSparse_long>(it->column());
          if (j >= i && (it->value() != 0. || j == i))
          {
            row_index[k] = j;
            values[k]    = it->value();
            ++k;
          }
        }
      }
      column_start[n] = k;

      if (permutation == nullptr)
        data_->factor = cholmod_l_analyze(A, &c);
      else
      {
        AssertDimension(permutation->size(), static_cast<std::size_t>(n));
        // Use the permutation exactly as given: one method, no
        // postordering (it could move the trailing dofs).
        const int nmethods   = c.nmethods;
        const int ordering   = c.method[0].ordering;
        const int postorder  = c.postorder;
        c.nmethods           = 1;
        c.method[0].ordering = CHOLMOD_GIVEN;
        c.postorder          = 0;
        data_->factor        = cholmod_l_analyze_p(
          A,
          const_cast<SuiteSparse_long *>(
            reinterpret_cast<const SuiteSparse_long *>(permutation->data())),
          nullptr,
          0,
          &c);
        c.nmethods           = nmethods;
        c.method[0].ordering = ordering;
        c.postorder          = postorder;
      }
      if (data_->factor == nullptr || c.status < CHOLMOD_OK)
      {
        cholmod_l_free_sparse(&A, &c);
        AssertThrow(false,
                    dealii::ExcMessage(
                      "CHOLMOD: symbolic analysis failed (status " +
                      std::to_string(c.status) + ")."));
      }
      if (!numeric)
      {
        cholmod_l_free_sparse(&A, &c);
        return;
      }
      // after the analysis CHOLMOD knows the factor's size and flops: say
      // what is coming (the numerical factorization cannot report progress)
      const double flops = c.fl;
      if (monitor_)
        monitor_("CHOLMOD factorization of order " + std::to_string(n) + ", " +
                 format("%.3g", c.lnz) + " factor nonzeros (" +
                 format("%.0f", 8e-6 * c.lnz) + " MB), " +
                 format("%.3g", flops * 1e-9) + " GFlop: about " +
                 format("%.2g", flops / measured_rate) + " s at " +
                 format("%.3g", measured_rate * 1e-9) + " GFlop/s");
      dealii::Timer numeric_timer;
      cholmod_l_factorize(A, data_->factor, &c);
      numeric_timer.stop();
      const int status = c.status;
      cholmod_l_free_sparse(&A, &c);
      AssertThrow(status != CHOLMOD_NOT_POSDEF,
                  dealii::ExcMessage(
                    "CHOLMOD: the stiffness matrix is not positive definite "
                    "(column " +
                    std::to_string(data_->factor->minor) +
                    "): is a body without enough Dirichlet conditions to "
                    "prevent rigid-body motions?"));
      AssertThrow(status >= CHOLMOD_OK,
                  dealii::ExcMessage("CHOLMOD: numerical factorization failed "
                                     "(status " +
                                     std::to_string(status) + ")."));

      if (flops >= 1e8 && numeric_timer.wall_time() > 0.)
        measured_rate = flops / numeric_timer.wall_time();
      if (monitor_)
        monitor_(
          "CHOLMOD factorization done in " +
          format("%.3g", numeric_timer.wall_time()) + " s (" +
          format("%.3g",
                 flops * 1e-9 / std::max(numeric_timer.wall_time(), 1e-9)) +
          " GFlop/s)");

      statistics_                 = Statistics();
      statistics_.setup_time      = timer.wall_time();
      statistics_.factor_nonzeros = c.lnz;
      statistics_.factor_flops    = c.fl;
    }


    void
    CholmodSolver::solve(dealii::Vector<double>       &x,
                         const dealii::Vector<double> &b) const
    {
      dealii::Timer timer;
      x = b;
      solve_in_turn({CHOLMOD_A}, x);
      statistics_.solve_time += timer.wall_time();
      ++statistics_.n_solves;
    }


    void
    CholmodSolver::solve_lower(dealii::Vector<double> &x) const
    {
      // a supernodal factor is L L' (not L D L'), so CHOLMOD_L is L^{-1}
      solve_in_turn({CHOLMOD_P, CHOLMOD_L}, x);
    }


    void
    CholmodSolver::solve_upper(dealii::Vector<double> &x) const
    {
      solve_in_turn({CHOLMOD_Lt, CHOLMOD_Pt}, x);
    }


    double
    CholmodSolver::reciprocal_condition() const
    {
      Assert(data_->factor != nullptr, dealii::ExcNotInitialized());
      return cholmod_l_rcond(data_->factor, &data_->common);
    }


    void
    CholmodSolver::solve_in_turn(const std::initializer_list<int> systems,
                                 dealii::Vector<double>          &x) const
    {
      Assert(data_->factor != nullptr, dealii::ExcNotInitialized());
      Assert(data_->factor->is_ll, dealii::ExcInternalError());
      AssertDimension(x.size(), static_cast<std::size_t>(data_->n));
      cholmod_common &c = data_->common;
      for (const int system : systems)
      {
        // wrap x without copying: CHOLMOD reads it and returns a new
        // dense vector
        cholmod_dense rhs;
        std::memset(&rhs, 0, sizeof(rhs));
        rhs.nrow  = data_->n;
        rhs.ncol  = 1;
        rhs.nzmax = data_->n;
        rhs.d     = data_->n;
        rhs.x     = x.begin();
        rhs.xtype = CHOLMOD_REAL;
        rhs.dtype = CHOLMOD_DOUBLE;

        cholmod_dense *solution =
          cholmod_l_solve(system, data_->factor, &rhs, &c);
        AssertThrow(solution != nullptr && c.status >= CHOLMOD_OK,
                    dealii::ExcMessage("CHOLMOD: solve failed (status " +
                                       std::to_string(c.status) + ")."));
        std::memcpy(x.begin(),
                    solution->x,
                    sizeof(double) * static_cast<std::size_t>(data_->n));
        cholmod_l_free_dense(&solution, &c);
      }
    }


    bool
    CholmodSolver::offers_schur_factor() const
    {
      return true;
    }


    void
    CholmodSolver::initialize_with_schur_factor(
      const dealii::SparseMatrix<double>                 &matrix,
      const std::vector<dealii::types::global_dof_index> &dofs,
      SchurFactor                                        &schur)
    {
      static_assert(sizeof(long) == sizeof(SuiteSparse_long),
                    "CHOLMOD's long integer is not long");
      dealii::Timer     timer;
      const std::size_t n = matrix.m();
      const std::size_t m = dofs.size();
      std::vector<bool> last(n, false);
      for (const auto dof : dofs)
      {
        AssertIndexRange(dof, n);
        AssertThrow(!last[dof],
                    dealii::ExcMessage("CHOLMOD: a Schur complement dof is "
                                       "given twice."));
        last[dof] = true;
      }

      // The configured fill-reducing ordering of the whole matrix, then the
      // dofs of the Schur complement moved to the end in the given order.
      // Only the ordering of this first analysis is used: its supernodal
      // symbolic factorization is skipped (0.25 of 2.7 s at 138,927 dofs).
      cholmod_common &c          = data_->common;
      const int       supernodal = c.supernodal;
      c.supernodal               = CHOLMOD_SIMPLICIAL;
      try
      {
        factorize(matrix, nullptr, /*numeric=*/false);
      }
      catch (...)
      {
        c.supernodal = supernodal;
        throw;
      }
      c.supernodal = supernodal;
      std::vector<long> permutation;
      permutation.reserve(n);
      const auto *order =
        static_cast<const SuiteSparse_long *>(data_->factor->Perm);
      for (std::size_t k = 0; k < n; ++k)
        if (!last[order[k]])
          permutation.push_back(order[k]);
      for (const auto dof : dofs)
        permutation.push_back(dof);
      factorize(matrix, &permutation);

      const cholmod_factor *L = data_->factor;
      AssertThrow(L->is_super && L->is_ll && L->xtype == CHOLMOD_REAL,
                  dealii::ExcMessage("CHOLMOD: expected a real supernodal "
                                     "LL' factor."));
      const auto *perm = static_cast<const SuiteSparse_long *>(L->Perm);
      for (std::size_t k = 0; k < m; ++k)
        AssertThrow(perm[n - m + k] == static_cast<SuiteSparse_long>(dofs[k]),
                    dealii::ExcMessage("CHOLMOD did not keep the given "
                                       "ordering of the Schur complement."));

      // Supernode s holds columns super[s] .. super[s+1]-1 as a dense
      // column-major block with rows s[pi[s]] .. s[pi[s+1]-1] (sorted, the
      // first ones those of the diagonal block) starting at x[px[s]].
      schur.dofs = dofs;
      schur.lower.assign(m * m, 0.);
      const auto *super = static_cast<const SuiteSparse_long *>(L->super);
      const auto *pi    = static_cast<const SuiteSparse_long *>(L->pi);
      const auto *px    = static_cast<const SuiteSparse_long *>(L->px);
      const auto *rows  = static_cast<const SuiteSparse_long *>(L->s);
      const auto *x     = static_cast<const double *>(L->x);
      const auto  first = static_cast<SuiteSparse_long>(n - m);
      for (std::size_t sn = 0; sn < L->nsuper; ++sn)
      {
        if (super[sn + 1] <= first)
          continue;
        const SuiteSparse_long n_rows = pi[sn + 1] - pi[sn];
        for (SuiteSparse_long j = std::max(super[sn], first); j < super[sn + 1];
             ++j)
          for (SuiteSparse_long r = 0; r < n_rows; ++r)
          {
            const SuiteSparse_long row = rows[pi[sn] + r];
            if (row < j)
              continue; // upper part of the diagonal block: not referenced
            schur.lower[(j - first) * m + (row - first)] =
              x[px[sn] + (j - super[sn]) * n_rows + r];
          }
      }
      statistics_.setup_time = timer.wall_time();
    }


    std::string
    CholmodSolver::name() const
    {
      return "cholmod";
    }
  } // namespace fem
} // namespace dualcontact
