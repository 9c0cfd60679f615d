#include <qp/apgd.h>
#include <qp/vector_helpers.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <cmath>

namespace dualcontact
{
  namespace qp
  {
    template <typename VectorType>
    APGD<VectorType>::APGD(const SolverParameters &parameters)
        : SolverBase<VectorType>("apgd", parameters)
    {
    }


    template <typename VectorType>
    SolverStatistics
    APGD<VectorType>::solve(const Problem<VectorType> &problem, VectorType &x)
    {
      const SolverParameters &prm   = this->prm;
      SolverStatistics        stats = this->start(problem, x);
      const double L = prm.apgd.l_factor * this->lambda_max(problem, stats);

      // Only A x^k is computed (one product per iteration); A y^k follows
      // by linearity from y^k = x^k + beta (x^k - x^{k-1}).
      VectorType Ax(x), Ax_old(x), g(x), y(x), gy(x), x_old(x);
      this->apply_hessian(problem, Ax, x, stats);
      g = Ax;
      g -= problem.b;
      y  = x;
      gy = g;
      // mu = 0 (thesis: the convexity constant is not known, and is zero
      // for an SPS Hessian); theta_0 = 1
      double theta = 1.;

      bool stop =
        this->check_stop(stats, this->criterion(problem, x, g, stats));
      while (!stop)
      {
        // x_old := x, Ax_old := Ax (swaps: x and Ax are overwritten next)
        x_old.swap(x);
        Ax_old.swap(Ax);
        // x^{k+1} = P(y^k - 1/L grad f(y^k))
        x = y;
        this->projected_step(problem, x, gy, 1. / L, stats);
        this->apply_hessian(problem, Ax, x, stats);
        ++stats.iterations;
        ++stats.n_expansions;

        // theta_{k+1}^2 = (1 - theta_{k+1}) theta_k^2  (mu = 0)
        const double t2        = theta * theta;
        const double theta_new = 0.5 * (-t2 + std::sqrt(t2 * t2 + 4. * t2));
        const double beta      = theta * (1. - theta) / (t2 + theta_new);
        theta                  = theta_new;
        // y^{k+1} = x^{k+1} + beta (x^{k+1} - x^k), gradient by linearity
        // g = Ax - b, y = (1 + beta) x - beta x_old, gy = (1 + beta) Ax -
        // beta Ax_old - b in one pass
        VectorKernels::extrapolate(x.locally_owned_size(),
                                   beta,
                                   x.begin(),
                                   x_old.begin(),
                                   Ax.begin(),
                                   Ax_old.begin(),
                                   problem.b.begin(),
                                   g.begin(),
                                   y.begin(),
                                   gy.begin());

        stop = this->check_stop(stats, this->criterion(problem, x, g, stats));
      }
      this->finish(problem, x, stats);
      return stats;
    }


    template class APGD<dealii::Vector<double>>;
    template class APGD<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
