#include <qp/augmented_lagrangian.h>
#include <qp/power_iteration.h>

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <algorithm>

namespace dualcontact
{
  namespace qp
  {
    template <typename VectorType>
    AugmentedLagrangian<VectorType>::AugmentedLagrangian(
      const Problem<VectorType> &problem,
      const bool                 coarse_projector,
      const double               rho,
      const VectorType          &x,
      SolverStatistics          &stats)
        : problem(problem)
        , eq(*problem.equality)
        , coarse_projector(coarse_projector)
        , rho(rho)
        , stats(stats)
        , b(problem.b)
        , lambda(eq.c)
        , Bx(eq.c)
        , residual(eq.c)
        , mu(eq.c)
        , BPv(eq.c)
        , Ax(x)
        , BtBx(x)
        , work(x)
        , g(x)
        , Pv(x)
        , projected_src(x)
    {
      lambda = 0.;
      if (coarse_projector)
      {
        // b := P(b - A x0), x0 = B'c: the linear term of the cost on the
        // kernel of B
        VectorType x0(x);
        eq.Tvmult(x0, eq.c);
        problem.hessian(Ax, x0);
        ++stats.n_hessian_products;
        b -= Ax;
        project(b);
      }
    }


    template <typename VectorType>
    void
    AugmentedLagrangian<VectorType>::project(VectorType &v)
    {
      eq.vmult(BPv, v);
      eq.Tvmult(Pv, BPv);
      v -= Pv;
    }


    template <typename VectorType>
    void
    AugmentedLagrangian<VectorType>::outer_hessian(VectorType       &dst,
                                                   const VectorType &src)
    {
      if (coarse_projector)
      {
        projected_src = src;
        project(projected_src);
        problem.hessian(dst, projected_src);
        project(dst);
      }
      else
        problem.hessian(dst, src);
    }


    template <typename VectorType>
    void
    AugmentedLagrangian<VectorType>::inner_hessian(VectorType       &dst,
                                                   const VectorType &src)
    {
      eq.vmult(Bx, src);
      eq.Tvmult(BtBx, Bx);
      if (coarse_projector)
      {
        // P A P src + rho B'B src with P src = src - B'B src: the B'B src
        // of the projection is the penalty's (one application of B and B'
        // less per product: each is a reduction under MPI and a coarse
        // solve in TFETI)
        projected_src = src;
        projected_src -= BtBx;
        problem.hessian(dst, projected_src);
        project(dst);
      }
      else
        problem.hessian(dst, src);
      ++stats.n_hessian_products;
      dst.add(rho, BtBx);
    }


    template <typename VectorType>
    std::function<
      std::function<void(VectorType &, const VectorType &)>(const VectorType &)>
    AugmentedLagrangian<VectorType>::inner_preconditioner()
    {
      if (!problem.free_set_preconditioner || !coarse_projector)
        return problem.free_set_preconditioner;
      // the inverse of P A P + rho B'B is approximated by P M P + B'B /
      // rho: the two parts act on orthogonal complements
      return [self = this, factory = problem.free_set_preconditioner](
               const VectorType &active_mask)
      {
        const auto M = factory(active_mask);
        return
          [self, M, projected = VectorType(self->g), Qv = VectorType(self->g)](
            VectorType &dst, const VectorType &src) mutable
        {
          projected = src;
          self->project(projected);
          M(dst, projected);
          self->project(dst);
          Qv = src;
          Qv -= projected; // B'B src = src - P src
          dst.add(1. / self->rho, Qv);
        };
      };
    }


    template <typename VectorType>
    Problem<VectorType>
    AugmentedLagrangian<VectorType>::inner_problem(const double lambda_max_A,
                                                   const SolverParameters &prm)
    {
      Problem<VectorType> inner;
      inner.constraints  = problem.constraints;
      inner.diagonal     = nullptr;
      inner.semidefinite = problem.semidefinite;
      inner.hessian      = [this](VectorType &dst, const VectorType &src)
      { inner_hessian(dst, src); };
      inner.free_set_preconditioner = inner_preconditioner();
      // lambda_max(A + rho B'B) is given to the inner solver once, so that
      // it does not run a power iteration per outer iteration
      if (coarse_projector)
        // P A P and rho B'B act on orthogonal complements
        inner.lambda_max = std::max(lambda_max_A, rho);
      else if (eq.norm_sq > 0.)
        // lambda_max(A + rho B'B) <= lambda_max(A) + rho ||B||^2: an upper
        // bound is a safe step length and costs no products
        inner.lambda_max = lambda_max_A + rho * eq.norm_sq;
      else
        inner.lambda_max = power_iteration<VectorType>(inner.hessian,
                                                       problem.b,
                                                       prm.power_max_iterations,
                                                       prm.power_tolerance,
                                                       prm.power_safety_factor)
                             .lambda_max;
      return inner;
    }


    template <typename VectorType>
    void
    AugmentedLagrangian<VectorType>::inner_right_hand_side(VectorType &inner_b)
    {
      inner_b = b;
      eq.Tvmult(work, lambda);
      inner_b -= work;
      eq.Tvmult(work, eq.c);
      inner_b.add(rho, work);
    }


    template <typename VectorType>
    double
    AugmentedLagrangian<VectorType>::equality_residual(const VectorType &x)
    {
      eq.vmult(residual, x);
      residual -= eq.c;
      return residual.l2_norm();
    }


    template <typename VectorType>
    double
    AugmentedLagrangian<VectorType>::value(const VectorType &x)
    {
      outer_hessian(Ax, x);
      ++stats.n_hessian_products;
      const double f    = 0.5 * (Ax * x) - b * x;
      const double norm = equality_residual(x);
      return f + (lambda * residual) + 0.5 * rho * norm * norm;
    }


    template <typename VectorType>
    const VectorType &
    AugmentedLagrangian<VectorType>::gradient(const VectorType &x)
    {
      outer_hessian(g, x);
      ++stats.n_hessian_products;
      g -= b;
      equality_residual(x);
      mu = lambda;
      mu.add(rho, residual);
      eq.Tvmult(work, mu);
      g += work;
      return g;
    }


    template <typename VectorType>
    void
    AugmentedLagrangian<VectorType>::update_multipliers(const VectorType &x)
    {
      equality_residual(x);
      lambda.add(rho, residual);
    }


    template <typename VectorType>
    const VectorType &
    AugmentedLagrangian<VectorType>::multipliers() const
    {
      return lambda;
    }


    template class AugmentedLagrangian<dealii::Vector<double>>;
    template class AugmentedLagrangian<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
