#pragma once

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <fem/cholmod_solver.h>

#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * TFETI's coarse problem: G = R'B' (one row per rigid-body mode of a
     * subdomain, one column per multiplier) and the factor of G G'.
     *
     * G G' is sparse: the modes of two subdomains meet only in the
     * multipliers whose rows touch both (neighbours across a gluing
     * interface, or across a contact zone), about 27 blocks of
     * dim (dim + 1) / 2 squared per block row of a 3D decomposition.  It
     * is factorized once by sparse Cholesky (CHOLMOD, fill-reducing
     * ordering): P G G' P' = L L'.  Then G~ = L^{-1} P G has orthonormal
     * rows, which is what SMALSE-M's projector I - G~'G~ needs, and
     * applying G~ or G~' costs one sparse product with G and one
     * triangular solve with L.  (A dense Cholesky of G G', as before, is
     * N^2 memory and N^3 work in the number N of subdomains: 4.8 GB and
     * minutes at 4,096 subdomains; doc/benchmarks/tfeti.md.)
     *
     * The recovery of the rigid-body amplitudes uses the same structure on
     * a subset of the columns: least_squares().
     */
    class CoarseProblem
    {
    public:
      /** Per multiplier (column of G), its entries (mode, value), modes
       *  ascending and distinct. */
      using Columns = std::vector<std::vector<std::pair<unsigned int, double>>>;

      /**
       * Takes G by columns (@p n_modes rows), assembles G G' and
       * factorizes it.  Throws (naming the cause, a rigid-body motion
       * nothing holds) when G G' is singular.
       */
      CoarseProblem(const unsigned int n_modes, Columns columns);

      unsigned int
      n_modes() const;

      /** dst = G src (dst sized n_modes()). */
      void
      vmult(dealii::Vector<double>       &dst,
            const dealii::Vector<double> &src) const;
      /** dst = G' src (dst sized to the number of multipliers). */
      void
      Tvmult(dealii::Vector<double>       &dst,
             const dealii::Vector<double> &src) const;

      /** dst += G_rows src: the columns @p rows of G times @p src[l]
       *  (the multiplier of rows[l]); dst sized n_modes(). */
      void
      add_columns(dealii::Vector<double>          &dst,
                  const std::vector<unsigned int> &rows,
                  const double                    *src) const;
      /** dst[l] := (G' src)(rows[l]) for the columns @p rows. */
      void
      Tvmult_columns(const dealii::Vector<double>    &src,
                     const std::vector<unsigned int> &rows,
                     double                          *dst) const;

      /** x := L^{-1} P x: G~ = L^{-1} P G, e~ = L^{-1} P e. */
      void
      orthonormalize(dealii::Vector<double> &x) const;
      /** x := P' L^{-T} x: G~' = G' P' L^{-T}. */
      void
      orthonormalize_transpose(dealii::Vector<double> &x) const;

      /**
       * alpha minimizing ||G_A' alpha - r_A||, A the columns for which
       * @p in_A is true (normal equations G_A G_A' alpha = G_A r_A, sparse
       * Cholesky).  Returns false, with the solution of the normal
       * equations shifted by 1e-12 times their largest diagonal entry (the
       * kernel directions get about 0), when G_A G_A' is singular.
       */
      bool
      least_squares(const std::function<bool(unsigned int)> &in_A,
                    const dealii::Vector<double>            &r,
                    dealii::Vector<double>                  &alpha) const;

      /** Nonzeros of G G' and of its Cholesky factor L. */
      std::size_t
      n_nonzeros() const;
      double
      n_factor_nonzeros() const;
      /** Wall time [s] of the assembly and factorization of G G'. */
      double
      setup_time() const;

    private:
      /** G_A G_A' (pattern and values) over the columns in @p in_A. */
      void
      assemble_normal_matrix(const std::function<bool(unsigned int)> &in_A,
                             dealii::SparsityPattern                 &pattern,
                             dealii::SparseMatrix<double> &matrix) const;

      unsigned int                        n_modes_;
      Columns                             columns_;
      dealii::SparsityPattern             pattern_;
      dealii::SparseMatrix<double>        ggt_;
      std::unique_ptr<fem::CholmodSolver> factor_;
      double                              setup_time_ = 0;
    };
  } // namespace decomposition
} // namespace dualcontact
