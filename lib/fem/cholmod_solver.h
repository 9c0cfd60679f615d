#pragma once

#include <fem/stiffness_solver.h>
#include <util/enum_names.h>

#include <initializer_list>
#include <string>

namespace dualcontact
{
  namespace fem
  {
    /**
     * Sparse Cholesky factorization K = L L' by CHOLMOD (SuiteSparse),
     * supernodal, with a fill-reducing ordering.
     *
     * The long-integer interface (cholmod_l_*) is used throughout: the int
     * interface broke down on a 408k-dof 3D elasticity matrix.  CHOLMOD's
     * supernodal kernels run on BLAS; with OpenBLAS a 92k-dof 3D matrix is
     * factorized in about 7 s, with reference BLAS in 44 s (scripts/setup
     * selects OpenBLAS).
     *
     * Only one triangle of the (symmetric) deal.II matrix is handed to
     * CHOLMOD, and explicit zeros (left by constraint condensation) are
     * dropped so that they create no fill.
     */
    class CholmodSolver : public StiffnessSolver
    {
    public:
      /** Fill-reducing orderings offered by CHOLMOD. */
      enum class Ordering
      {
        automatic, ///< CHOLMOD's default strategy (AMD, METIS if fill is high)
        amd,
        metis,
        nested_dissection
      };

      explicit CholmodSolver(const Ordering ordering = Ordering::automatic);
      ~CholmodSolver() override;

      void
      initialize(const dealii::SparseMatrix<double> &matrix) override;

      void
      solve(dealii::Vector<double>       &x,
            const dealii::Vector<double> &b) const override;

      /**
       * The two halves of solve() for the factor P K P' = L L' (P the
       * fill-reducing permutation): x := L^{-1} P x.  With them L^{-1} P G
       * has orthonormal rows where K = G G' (decomposition::CoarseProblem).
       */
      void
      solve_lower(dealii::Vector<double> &x) const;

      /** x := P' L^{-T} x, the transpose of solve_lower(). */
      void
      solve_upper(dealii::Vector<double> &x) const;

      /**
       * CHOLMOD's estimate of the reciprocal condition number of the
       * factorized matrix, (min_i L_ii / max_i L_ii)^2: a tiny value is a
       * matrix that is singular up to round-off (the factorization itself
       * only stops at a pivot that is not positive).
       */
      double
      reciprocal_condition() const;

      bool
      offers_schur_factor() const override;

      /**
       * Orders @p dofs last (the others keep the order the configured
       * ordering gives them, without postordering), factorizes, and reads
       * the trailing block of the supernodal factor into @p schur.  Moving a
       * few boundary dofs to the end changes the fill little: eliminating
       * the rest first only removes paths through them.
       */
      void
      initialize_with_schur_factor(
        const dealii::SparseMatrix<double>                 &matrix,
        const std::vector<dealii::types::global_dof_index> &dofs,
        SchurFactor                                        &schur) override;

      std::string
      name() const override;

      /** The names of Ordering (`Stiffness solver/Ordering'). */
      static constexpr util::EnumNames<Ordering, 4> ordering_names{
        "CHOLMOD ordering (`Stiffness solver/Ordering')",
        {{"automatic", "amd", "metis", "nested dissection"}},
      };

    private:
      void
      free_factor();

      /** x := the solution of CHOLMOD's @p systems (CHOLMOD_A, _L, _P,
       *  ...) applied in turn, each to the result of the one before. */
      void
      solve_in_turn(const std::initializer_list<int> systems,
                    dealii::Vector<double>          &x) const;

      /**
       * Analyse and (if @p numeric) factorize @p matrix; with
       * @p permutation (size n) that fill-reducing permutation is used as
       * given, else the configured ordering.
       */
      void
      factorize(const dealii::SparseMatrix<double> &matrix,
                const std::vector<long>            *permutation,
                const bool                          numeric = true);

      Ordering ordering_;
      /** Opaque CHOLMOD objects (cholmod_common, cholmod_factor). */
      struct Data;
      std::unique_ptr<Data> data_;
    };
  } // namespace fem
} // namespace dualcontact
