#include <qp/spg_qp.h>
#include <qp/vector_helpers.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>

namespace dualcontact
{
  namespace qp
  {
    template <typename VectorType>
    SPGQP<VectorType>::SPGQP(const SolverParameters &parameters)
        : SolverBase<VectorType>("spg-qp", parameters)
    {
    }


    template <typename VectorType>
    SolverStatistics
    SPGQP<VectorType>::solve(const Problem<VectorType> &problem, VectorType &x)
    {
      const SolverParameters &prm   = this->prm;
      SolverStatistics        stats = this->start(problem, x);
      const double            lmax  = this->lambda_max(problem, stats);

      VectorType g(x), d(x), Ad(x);
      this->apply_hessian(problem, g, x, stats);
      g -= problem.b;
      // f = 1/2 x'Ax - b'x = 1/2 (g - b)'x: no product needed
      const auto cost = [&]() { return internal::cost(x, g, problem.b); };
      double     f    = cost();
      std::deque<double> recent(1, f); // the last m cost values (GLL)
      double             alpha = prm.spg.alpha0_factor / lmax;
      // the sufficient-decrease parameter of the Armijo condition (2.8);
      // algorithm 4 uses its complement (it relabels gamma := 1 - gamma)
      const double gamma = 1. - prm.spg.gamma;

      bool stop =
        this->check_stop(stats, this->criterion(problem, x, g, stats));
      while (!stop)
      {
        // d = P(x - alpha g) - x
        d = x;
        this->projected_step(problem, d, g, alpha, stats);
        d -= x;
        this->apply_hessian(problem, Ad, d, stats);
        // d'Ad, d'd, g'd in one pass
        const std::array<double, 3> dots = internal::dots(d, Ad, g);
        const double                dAd = dots[0], dd = dots[1], gd = dots[2];
        ++stats.iterations;
        ++stats.n_bb;
        if (dd == 0.)
        {
          // x = P(x - alpha g): x is stationary, the criterion must say
          // so; if it does not (tolerance below rounding) stop honestly
          stop = this->check_stop(stats, this->criterion(problem, x, g, stats));
          if (!stop)
          {
            stats.reason  = ConvergenceReason::stagnation;
            stats.message = "projected step is zero but the "
                            "criterion is above the tolerance";
            stop          = true;
          }
          break;
        }
        if (!std::isfinite(dAd) || !std::isfinite(gd))
        {
          stats.reason  = ConvergenceReason::non_finite;
          stats.message = "d'Ad or g'd is not finite";
          break;
        }

        // the closed-form step interval of 2.1.4: any beta in
        // [sigma_1, min(sigma_2, beta_hat)] satisfies the generalized
        // Armijo condition; take the largest
        double beta = prm.spg.sigma2;
        if (dAd > 0.)
        {
          const double f_max = *std::max_element(recent.begin(), recent.end());
          const double xi    = std::max(0., (f_max - f) / dAd);
          const double beta_bar = -gd / dAd;
          const double beta_hat =
            gamma * beta_bar +
            std::sqrt(gamma * gamma * beta_bar * beta_bar + 2. * xi);
          beta = std::min(prm.spg.sigma2, beta_hat);
        }
        else if (gd >= 0.)
        {
          // zero curvature and not a descent direction: cannot happen
          // for d = P(x - alpha g) - x != 0 unless A or P is broken
          stats.reason  = ConvergenceReason::breakdown;
          stats.message = "d'Ad <= 0 and g'd >= 0";
          break;
        }
        // (dAd <= 0 with g'd < 0: the cost decreases along d without
        // bound inside the segment; beta = sigma_2 keeps x feasible)

        // x += beta d, g += beta Ad in one pass, then the cost
        VectorKernels::step(x.locally_owned_size(),
                            beta,
                            d.begin(),
                            Ad.begin(),
                            x.begin(),
                            g.begin());
        f = cost();
        recent.push_back(f);
        while (recent.size() > std::max(1u, prm.spg.m))
          recent.pop_front();
        // BB step length for the next iteration: (d,d)/(d,Ad), the
        // inverse Rayleigh quotient, within [1/lambda_max, 1/lambda_min]
        alpha = dAd > 0. ? dd / dAd : prm.spg.alpha0_factor / lmax;

        // with the cost: a new least cost is progress (stagnation test)
        stop =
          this->check_stop(stats, this->criterion(problem, x, g, stats), f);
      }
      this->finish(problem, x, stats);
      return stats;
    }


    template class SPGQP<dealii::Vector<double>>;
    template class SPGQP<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
