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
 *
 * Why the in-place recompute: MPRGP meets a new active set after every
 * half-step and every proportioning step, and a full ML setup (the
 * aggregation above all) costs several times a whole PCG phase (84% to
 * 95% of the wall time on the membrane).  Consecutive active sets differ
 * at the rim of the contact zone only, so the matrix keeps one Trilinos
 * copy of A's full sparsity pattern whose active rows/columns are
 * overwritten in place, and ML recomputes its hierarchy on the aggregates
 * of the last full setup (ML's ReComputePreconditioner through
 * PreconditionAMG::reinit(): new smoothed prolongators, coarse operators
 * and smoothers, no new aggregation).
 */
#ifndef dualcontact_qp_free_set_amg_h
#define dualcontact_qp_free_set_amg_h

#include <qp/problem.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace dualcontact
{
  namespace qp
  {
    /**
     * Factory of AMG preconditioners of A_FF for the free sets MPRGP meets
     * (`Preconditioner = amg`).  Holds a reference to A (which must outlive
     * it and every operator it returned), one Trilinos copy of A with A's
     * full sparsity pattern, and one ML hierarchy.  Serial
     * (dealii::Vector<double>), like qpsolve.
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
        /**
         * ML's strength-of-connection threshold of the aggregation.  0.02
         * (deal.II's default is 1e-4): on the membranes of
         * doc/benchmarks/membrane.md ("Session 17") equal or fewer
         * active-set changes and set-ups on all 10 cases measured (PERMON's
         * variant h = 50-800 at p = 0.5, h = 400 at p = 0.1 / 0.9, the
         * thesis' at h = 200 / 400): h = 400, p = 0.5 1.43 -> 1.15 s,
         * p = 0.9 2.45 -> 1.48 s, the others within the run-to-run spread.
         */
        double aggregation_threshold = 0.02;
        /// smoother sweeps per level (deal.II default 2)
        unsigned int smoother_sweeps = 2;
        /**
         * ML's prolongator damping ("aggregation: damping factor", ML's
         * default 4/3): the smoothed prolongator is (I - omega D^-1 A) P
         * with omega = damping / lambda_max(D^-1 A); 0 keeps the tentative
         * (piecewise constant) prolongator, whose coarse operators P'AP
         * cost far fewer sparse products to recompute.
         */
        double prolongator_damping = 4. / 3.;
        /// V-cycles per application (deal.II default 1)
        unsigned int n_cycles = 1;
        /**
         * true: ML aggregates A itself (every unknown free) once, at the
         * first build() after construction or reset(), and every active
         * set gets an in-place recompute of the hierarchy on those
         * aggregates (PreconditionAMG::reinit(): smoothed prolongators,
         * coarse operators, smoothers).  false: a full ML setup (new
         * aggregation) on the restricted matrix of every active set.  Why
         * A's aggregates: aggregates of a restricted matrix leave its
         * active unknowns out, and when those unknowns are freed later the
         * coarse spaces miss them (on the membrane at h = 200, aggregates
         * kept from an intermediate active set cost 32 CG steps against
         * 19 with A's; doc/benchmarks/membrane.md).
         */
        bool reuse_aggregates = true;
        /**
         * A new active set that differs from the one the hierarchy was
         * last computed for in at most this fraction of the unknowns
         * (dimensionless, in [0, 1]) keeps that hierarchy unchanged: no
         * setup or recompute; M_F^{-1} is then the old operator restricted
         * to the new free set by the solver, still symmetric positive
         * definite on it, only a less exact inverse of A_FF.  0: a
         * setup or recompute for every new set.
         */
        double keep_fraction = 0.;
      };

      /// with the default Parameters
      explicit FreeSetAMG(const dealii::SparseMatrix<double> &A);
      FreeSetAMG(const dealii::SparseMatrix<double> &A,
                 const Parameters                   &parameters);

      /**
       * The AMG of A_FF for the free set given by @p active_mask (1 on
       * active unknowns) as M_F^{-1}: a full ML setup, an in-place
       * recompute or the current hierarchy (Parameters).  There is one
       * hierarchy: the operator returned is valid until the next build() (MPRGP
       * drops it there) and as long as this object lives.
       */
      typename Problem<Vec>::FreeSetPreconditioner
      build(const Vec &active_mask);

      /// build() as the factory Problem::free_set_preconditioner wants
      /// (captures this object, which must outlive the solve)
      std::function<typename Problem<Vec>::FreeSetPreconditioner(const Vec &)>
      factory();

      /// forget the hierarchy: the next build() is a full setup (call it
      /// between independent solves, e.g. qpsolve --repeat, so that each
      /// pays for its aggregation)
      void
      reset();

      /// full ML setups (with aggregation) since construction
      unsigned int
      n_full_setups() const
      {
        return full_setups;
      }

      /// build() calls that kept the current hierarchy
      /// (Parameters::keep_fraction) since construction
      unsigned int
      n_kept() const
      {
        return kept;
      }

      /// in-place recomputes (ML ReComputePreconditioner) since
      /// construction
      unsigned int
      n_recomputes() const
      {
        return recomputes;
      }

    private:
      const dealii::SparseMatrix<double> &matrix;
      const Parameters                    parameters;
      /// A with the active rows and columns replaced by identity rows, in
      /// Trilinos format with A's whole sparsity pattern (so that every
      /// active set has the same pattern and ML can recompute in place)
      dealii::TrilinosWrappers::SparseMatrix restricted;
      /// A's entries and their global columns, in the storage order of
      /// @p restricted (row by row)
      std::vector<double>       original;
      std::vector<unsigned int> column;
      /// the one ML hierarchy (shared with the operators returned)
      std::shared_ptr<dealii::TrilinosWrappers::PreconditionAMG> amg;
      /// the active mask the hierarchy was last computed for (empty: no
      /// hierarchy yet)
      std::vector<bool> computed_mask;
      /// the value of those identity rows: the mean of diag(A), so that
      /// they do not change the scale ML sees
      double       unit        = 1.;
      unsigned int full_setups = 0;
      unsigned int recomputes  = 0;
      unsigned int kept        = 0;

      /// ML's AdditionalData from the parameters
      dealii::TrilinosWrappers::PreconditionAMG::AdditionalData
      additional_data() const;
      /// ML's parameter list: additional_data()'s, and the prolongator
      /// damping
      Teuchos::ParameterList
      ml_parameters();
      /// the null space the list may point to (kept alive with it)
      std::unique_ptr<Epetra_MultiVector> constant_modes;
      /// overwrite @p restricted's entries: A's, with identity rows and
      /// zero couplings for the unknowns where @p active_mask is nonzero
      /// (no mask: A itself)
      void
      set_entries(const Vec *active_mask);
    };
  } // namespace qp
} // namespace dualcontact

#endif
