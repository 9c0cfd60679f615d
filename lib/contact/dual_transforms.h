#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <contact/multiplier_distribution.h>
#include <qp/problem.h>

#include <functional>
#include <memory>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * @file dual_transforms.h
     * The transforms between the dual and the QP the solvers see
     * (PERMON's QP transforms: each makes a new QP and knows how its
     * solution maps back to the one before):
     *  - LambdaMaxScaling: Hessian F / s, linear term d / s, s =
     *    lambda_max(F); the minimizer is unchanged, nothing to map back;
     *  - OrthonormalEqualities: G lambda = e as G~ lambda = e~ with
     *    orthonormal rows (G~ = L^{-1} G, e~ = L^{-1} e, G G' = L L');
     *    the feasible set is unchanged, so is lambda (the equality
     *    multipliers would map back as mu = L^{-T} mu~; nobody reads them).
     * The dualization itself maps back by the recovery (DualProblem::
     * recover(): u = K^#(f - B'lambda) + R alpha).  Why the dual QP is
     * scaled: lib/contact/README.md, "Scaling".
     */

    /**
     * s = lambda_max(F) by power iteration, and the QP with F / s and
     * d / s (Hessian of norm 1, a right-hand side that is a force like the
     * multipliers and the equality residual).
     */
    class LambdaMaxScaling
    {
    public:
      using VectorType = dealii::Vector<double>;

      /**
       * Power iteration on @p F from @p start (200 iterations at most,
       * relative tolerance 1e-6).  Throws if F is zero or not finite.
       */
      LambdaMaxScaling(
        const std::function<void(VectorType &, const VectorType &)> &F,
        const VectorType                                            &start);

      /** s = lambda_max(F) [m/N]. */
      double
      scale() const;
      /** Products with F spent on the estimate. */
      unsigned int
      n_products() const;

      /**
       * @p problem (Hessian F, linear term d) becomes the scaled QP:
       * Hessian F / s, linear term d / s, lambda_max 1.05 (the power
       * iteration approaches from below).
       */
      template <typename V>
      void
      transform(qp::Problem<V> &problem) const
      {
        const std::function<void(V &, const V &)> hessian = problem.hessian;
        const double                              s       = scale_;
        problem.hessian = [hessian, s](V &dst, const V &src)
        {
          hessian(dst, src);
          dst /= s;
        };
        problem.b /= s;
        problem.lambda_max = 1.05;
      }

      /** The scaled QP's minimizer is the unscaled one's. */
      template <typename V>
      void
      map_back(V &) const
      {
      }

    private:
      double       scale_      = 1.;
      unsigned int n_products_ = 0;
    };


    /**
     * The equality constraints G lambda = e (G = R'B', one row per
     * rigid-body mode) with orthonormal rows: G~ = L^{-1} G, e~ = L^{-1} e,
     * G G' = L L', by modified Gram-Schmidt on the rows (applied to e
     * alike), so that ||G~|| = 1 and SMALSE-M's penalty and tests compare
     * forces with forces.  A row that vanishes is a rigid-body motion no
     * contact constraint restrains: an error.
     */
    class OrthonormalEqualities
    {
    public:
      using VectorType        = dealii::Vector<double>;
      using DistributedVector = dealii::TrilinosWrappers::MPI::Vector;

      OrthonormalEqualities(const std::vector<VectorType> &G_rows,
                            const VectorType              &e);

      /** Rows of G (rigid-body modes). */
      unsigned int
      n_rows() const;

      /** G~ and e~ for a QP on all @p n_multipliers multipliers. */
      std::shared_ptr<qp::EqualityConstraints<VectorType>>
      constraints(const unsigned int n_multipliers) const;

      /**
       * The rows of G~ and e~ on process 0 of @p owners' communicator
       * (collective); before distributed_constraints().
       */
      void
      distribute(const MultiplierDistribution &owners);

      /**
       * G~ and e~ for a QP on the multipliers of @p owners (which must
       * outlive the result): G~ x sums the owned partial dot products;
       * G~'y sends the few coefficients to every process, which forms
       * its owned entries.
       */
      std::shared_ptr<qp::EqualityConstraints<DistributedVector>>
      distributed_constraints(const MultiplierDistribution &owners,
                              const unsigned int n_multipliers) const;

      /** The same as the last with the map back of the minimizer: none
       *  (the feasible set is unchanged). */
      template <typename V>
      void
      map_back(V &) const
      {
      }

    private:
      std::vector<VectorType> rows_;
      VectorType              rhs_;
      /** The rows of G~ (equality multipliers) live on process 0. */
      dealii::IndexSet                   owned_modes_;
      std::unique_ptr<DistributedVector> rhs_distributed_;
    };
  } // namespace contact
} // namespace dualcontact
