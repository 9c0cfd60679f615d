#pragma once

#include <deal.II/lac/vector.h>

#include <fclib/triplets.h>
#include <util/enum_names.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace fclib
  {
    /** How W is kept for its products. */
    enum class Storage
    {
      /** dense when at least a quarter of the entries are non-zero */
      automatic,
      dense,
      sparse
    };

    /** The names of Storage: "auto", "dense", "sparse". */
    inline constexpr util::EnumNames<Storage, 3> storage_names{
      "storage of W",
      {{"auto", "dense", "sparse"}},
    };

    /**
     * The products with the Delassus matrix W of a local problem: u = W r
     * and the Hessian W_s r of 1/2 r'W r, W_s = (W + W')/2.
     *
     * Why a class of its own: W of a problem reduced from a global one (or
     * exported by a scene, W = B K^-1 B') is dense — every contact sees every
     * other through the elastic bodies — and the solvers spend nearly all
     * their time in these products.  A dense W is therefore kept as a dense
     * column-major array and multiplied by BLAS (dsymv on the symmetric part,
     * which reads one triangle; dgemv for W itself), a sparse one (e.g. a
     * rigid-body problem with few neighbours per contact) as a deal.II sparse
     * matrix.  W_s is formed once (not as (W r + W'r)/2 per product); for a
     * symmetric W it is W itself, so a Hessian product is one product with
     * W.
     */
    class DelassusOperator
    {
    public:
      DelassusOperator() = default;
      /** @p W square; @p storage: dense, sparse, or chosen by density. */
      DelassusOperator(const Triplets &W,
                       const Storage   storage = Storage::automatic);

      unsigned int
      size() const;
      /** Whether the products use the dense arrays. */
      bool
      dense() const;
      /** Non-zero entries of W (stored entries that are not 0). */
      std::size_t
      n_nonzero() const;

      /** The matrix as read (for writing it, listing entries, element access).
       */
      const dealii::SparseMatrix<double> &
      matrix() const;

      /** dst = W src. */
      void
      vmult(dealii::Vector<double>       &dst,
            const dealii::Vector<double> &src) const;

      /** dst = W_s src = (W + W')/2 src, the Hessian of 1/2 r'W r. */
      void
      symmetric_vmult(dealii::Vector<double>       &dst,
                      const dealii::Vector<double> &src) const;

      /**
       * dst += W_s v for a v that is zero outside @p indices: the columns
       * of W_s for those indices only, at (number of indices) / n of a
       * product's cost.  fclib::LocalSolver corrects the gradient a
       * Coulomb QP starts from with it when the new slip bounds move a few
       * contacts of the start (qp::Problem::hessian_add_sparse).
       */
      void
      add_symmetric_columns(dealii::Vector<double>         &dst,
                            const dealii::Vector<double>   &v,
                            const std::vector<std::size_t> &indices) const;

      /**
       * S W_s S for S = diag(@p s), dense column-major with both triangles,
       * when W is stored dense (else empty): the Hessian of the
       * contact-scaled QPs of fclib::LocalSolver, formed once so that each
       * of their products is one dsymv (dense_vmult()) instead of a dsymv,
       * a copy and two scalings, which on the small Hertz exports cost a
       * tenth of a product's time.
       */
      std::vector<double>
      scaled_dense_symmetric(const dealii::Vector<double> &s) const;

      /// dst = A src for a symmetric A from scaled_dense_symmetric()
      static void
      dense_vmult(const std::vector<double>    &A,
                  dealii::Vector<double>       &dst,
                  const dealii::Vector<double> &src);

      /// dst += A v for such an A and a v that is zero outside @p indices
      /// (the columns of those indices; see add_symmetric_columns())
      static void
      dense_add_columns(const std::vector<double>      &A,
                        dealii::Vector<double>         &dst,
                        const dealii::Vector<double>   &v,
                        const std::vector<std::size_t> &indices);

      /** dst = W_a src = (W - W')/2 src, the part 1/2 r'W r does not see. */
      void
      antisymmetric_vmult(dealii::Vector<double>       &dst,
                          const dealii::Vector<double> &src) const;

      /**
       * Rows of W without a non-zero entry: unknowns that no force
       * reaches (e.g. the tangent of a contact node whose displacement in
       * that direction is prescribed), zero-curvature directions of 1/2 r'W r
       * that are decoupled from all others.
       */
      unsigned int
      n_zero_rows() const;

      /** max |W_ij - W_ji| / max |W_ij| (computed once). */
      double
      asymmetry() const;

      /**
       * The numerical rank of W_s: the number of pivots of its Cholesky
       * factorization with complete pivoting (LAPACK dpstrf) above
       * @p relative_tolerance times the largest diagonal entry.  A rank
       * below size() means W_s is singular (rigid-body problems) or so
       * ill-conditioned that it is numerically.  Costs a dense n^3/3
       * factorization: returns -1 without computing when size() exceeds
       * @p max_size.
       */
      int
      numerical_rank(const double       relative_tolerance,
                     const unsigned int max_size = 4000) const;

    private:
      unsigned int      n_         = 0;
      bool              dense_     = false;
      std::size_t       nonzero_   = 0;
      unsigned int      zero_rows_ = 0;
      double            asymmetry_ = 0;
      OwnedSparseMatrix W_;
      /** W_s when W is not symmetric (sparse storage). */
      OwnedSparseMatrix W_s_;
      /** Column-major W and, if W is not symmetric, W_s (dense storage). */
      std::vector<double>            dense_W_, dense_W_s_;
      mutable dealii::Vector<double> work_;
    };
  } // namespace fclib
} // namespace dualcontact
