#include <qp/pbbf.h>
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
    PBBf<VectorType>::PBBf(const SolverParameters &parameters)
        : SolverBase<VectorType>("pbbf", parameters)
    {
    }


    template <typename VectorType>
    SolverStatistics
    PBBf<VectorType>::solve(const Problem<VectorType> &problem, VectorType &x)
    {
      const SolverParameters &prm   = this->prm;
      SolverStatistics        stats = this->start(problem, x);
      this->lambda_max(problem, stats);
      const double alpha_bar = stats.alpha_bar;

      VectorType g(x), x_old(x), g_old(x), x_min(x), g_min(x);
      const auto cost = [&](const VectorType &point, const VectorType &gradient)
      { return internal::cost(point, gradient, problem.b); };
      // dst = P(src - alpha g_src), g_dst = A dst - b
      const auto projected_step = [&](VectorType       &dst,
                                      VectorType       &g_dst,
                                      const VectorType &src,
                                      const VectorType &g_src,
                                      const double      alpha)
      {
        dst = src;
        this->projected_step(problem, dst, g_src, alpha, stats);
        this->apply_hessian(problem, g_dst, dst, stats);
        g_dst -= problem.b;
      };

      this->apply_hessian(problem, g, x, stats);
      g -= problem.b;
      bool stop =
        this->check_stop(stats, this->criterion(problem, x, g, stats));
      if (!stop)
      {
        // table 14: x^1 = P(x^0 - alpha_bar g^0)
        x_old = x;
        g_old = g;
        projected_step(x, g, x_old, g_old, alpha_bar);
        ++stats.iterations;
        ++stats.n_expansions;
        stop = this->check_stop(stats, this->criterion(problem, x, g, stats));
      }
      x_min              = x;
      g_min              = g;
      double       f_min = cost(x_min, g_min);
      unsigned int k_hat = 0;

      while (!stop)
      {
        // BB step length from s = x^k - x^{k-1}, As = g^k - g^{k-1}:
        // no extra product
        // s = x - x_old, y = g - g_old = A s: s's and s'y in one pass
        VectorKernels::Lanes ss_lanes, sy_lanes;
        VectorKernels::step_differences(x.locally_owned_size(),
                                        x.begin(),
                                        g.begin(),
                                        x_old.begin(),
                                        g_old.begin(),
                                        false,
                                        ss_lanes,
                                        sy_lanes);
        const double ss       = internal::sum(ss_lanes.total(), x);
        const double sAs      = internal::sum(sy_lanes.total(), x);
        const double alpha_bb = (sAs > 0. && ss > 0.) ? ss / sAs : alpha_bar;
        if (!std::isfinite(alpha_bb))
        {
          stats.reason  = ConvergenceReason::non_finite;
          stats.message = "BB step length is not finite";
          break;
        }
        x_old = x;
        g_old = g;
        projected_step(x, g, x_old, g_old, alpha_bb);
        ++stats.iterations;
        ++stats.n_bb;

        // fall-back update: remember a point of sufficient decrease
        double f = cost(x, g);
        if (f < f_min)
        {
          projected_step(x_min, g_min, x, g, alpha_bar);
          f_min = cost(x_min, g_min);
          k_hat = 0;
        }
        else
          ++k_hat;

        // fall-back application: K steps without improvement
        if (k_hat >= prm.pbbf.k)
        {
          projected_step(x, g, x_min, g_min, alpha_bar);
          x_min = x;
          g_min = g;
          f_min = cost(x_min, g_min);
          f     = f_min; // x is x_min now
          k_hat = 0;
          ++stats.n_fall_back;
        }
        // with the cost of x: a new least cost is progress (stagnation
        // test)
        stop =
          this->check_stop(stats, this->criterion(problem, x, g, stats), f);
      }
      this->finish(problem, x, stats);
      return stats;
    }


    template class PBBf<dealii::Vector<double>>;
    template class PBBf<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
