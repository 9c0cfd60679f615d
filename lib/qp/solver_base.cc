#include <qp/kkt_residuals.h>
#include <qp/power_iteration.h>
#include <qp/solver_base.h>
#include <qp/vector_helpers.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <type_traits>

namespace dualcontact
{
  namespace qp
  {
    namespace
    {
      std::string
      sci(const double v)
      {
        char buf[32];
        std::snprintf(buf, sizeof(buf), "%.3e", v);
        return buf;
      }
    } // namespace


    template <typename VectorType>
    SolverBase<VectorType>::SolverBase(const std::string      &name,
                                       const SolverParameters &parameters)
        : solver_name(name)
        , prm(parameters)
    {
      prm.check();
    }


    template <typename VectorType>
    const std::string &
    SolverBase<VectorType>::name() const
    {
      return solver_name;
    }


    template <typename VectorType>
    const SolverParameters &
    SolverBase<VectorType>::parameters() const
    {
      return prm;
    }


    template <typename VectorType>
    void
    SolverBase<VectorType>::set_tolerance(const double       tolerance,
                                          const unsigned int max_iterations)
    {
      SolverParameters changed = prm;
      changed.tolerance        = tolerance;
      changed.max_iterations   = max_iterations;
      AssertThrow(tolerance > 0. && std::isfinite(tolerance),
                  dealii::ExcMessage(solver_name +
                                     ": the tolerance must be positive and "
                                     "finite, not " +
                                     std::to_string(tolerance)));
      AssertThrow(max_iterations > 0,
                  dealii::ExcMessage(solver_name +
                                     ": the iteration limit must be positive"));
      prm = changed;
    }


    template <typename VectorType>
    const VectorType *
    SolverBase<VectorType>::final_gradient() const
    {
      return last_gradient_valid ? &last_gradient : nullptr;
    }


    template <typename VectorType>
    double
    SolverBase<VectorType>::equality_residual() const
    {
      return 0.;
    }


    template <typename VectorType>
    SolverStatistics
    SolverBase<VectorType>::start(const Problem<VectorType> &problem,
                                  VectorType                &x)
    {
      timer.restart();
      last_gradient_valid = false;
      AssertThrow(static_cast<bool>(problem.hessian),
                  dealii::ExcMessage(solver_name +
                                     ": the problem has no Hessian operator"));
      AssertThrow(x.size() == problem.b.size(),
                  dealii::ExcMessage(solver_name +
                                     ": x and b differ in size (" +
                                     std::to_string(x.size()) + " vs " +
                                     std::to_string(problem.b.size()) + ")"));
      AssertThrow(!problem.constraints || problem.constraints->is_finalized(),
                  dealii::ExcMessage(solver_name +
                                     ": the constraint set was not finalized"));
      SolverStatistics stats;
      stats.solver = solver_name;
      stats.stopping_criterion =
        stopping_criterion_names.name(prm.stopping_criterion);
      stats.tolerance     = prm.tolerance;
      const double norm_b = internal::norm(problem.b);
      AssertThrow(std::isfinite(norm_b),
                  dealii::ExcMessage(solver_name + ": b is not finite"));
      // b = 0 would make every relative test unreachable; use an absolute
      // test then.
      stats.norm_b       = norm_b > 0. ? norm_b : 1.;
      best_criterion     = std::numeric_limits<double>::infinity();
      cost_at_progress   = std::numeric_limits<double>::infinity();
      progress_iteration = 0;
      progress_problem   = &problem;
      progress_x         = &x;
      next_report_time   = 0.;
      if (problem.constraints)
        project(problem, x, stats);
      return stats;
    }


    template <typename VectorType>
    void
    SolverBase<VectorType>::apply_hessian(const Problem<VectorType> &problem,
                                          VectorType                &dst,
                                          const VectorType          &src,
                                          SolverStatistics &stats) const
    {
      problem.hessian(dst, src);
      ++stats.n_hessian_products;
    }


    template <typename VectorType>
    void
    SolverBase<VectorType>::project(const Problem<VectorType> &problem,
                                    VectorType                &x,
                                    SolverStatistics          &stats) const
    {
      if (problem.constraints)
      {
        problem.constraints->project(x);
        ++stats.n_projections;
      }
    }


    template <typename VectorType>
    void
    SolverBase<VectorType>::projected_step(const Problem<VectorType> &problem,
                                           VectorType                &x,
                                           const VectorType          &g,
                                           const double               alpha,
                                           SolverStatistics &stats) const
    {
      if (problem.constraints)
      {
        problem.constraints->projected_step(x, g, alpha, false);
        ++stats.n_projections;
      }
      else
        x.add(-alpha, g);
    }


    template <typename VectorType>
    double
    SolverBase<VectorType>::lambda_max(const Problem<VectorType> &problem,
                                       SolverStatistics          &stats) const
    {
      double value = problem.lambda_max;
      AssertThrow(value >= 0. && std::isfinite(value),
                  dealii::ExcMessage(solver_name +
                                     ": lambda_max must be >= 0 and finite"));
      if (value == 0.)
      {
        const PowerIterationResult r =
          power_iteration<VectorType>(problem.hessian,
                                      problem.b,
                                      prm.power_max_iterations,
                                      prm.power_tolerance,
                                      prm.power_safety_factor);
        stats.n_hessian_products += r.n_products;
        value = r.lambda_max;
      }
      stats.lambda_max = value;
      stats.alpha_bar  = prm.alpha_bar_factor / value;
      return value;
    }


    template <typename VectorType>
    double
    SolverBase<VectorType>::criterion(const Problem<VectorType> &problem,
                                      const VectorType          &x,
                                      const VectorType          &g,
                                      const SolverStatistics    &stats) const
    {
      if (!problem.constraints)
        return internal::norm(g);
      const SeparableSet<VectorType> &set = *problem.constraints;
      switch (prm.stopping_criterion)
      {
        case StoppingCriterion::projected:
        {
          const GradientNorms n = set.gradient_norms(x, g);
          return std::sqrt(n.free_sq + n.chopped_sq);
        }
        case StoppingCriterion::reduced:
          Assert(stats.alpha_bar > 0., dealii::ExcInternalError());
          return set.reduced_gradient_norm(x, g, stats.alpha_bar);
        case StoppingCriterion::reduced_projected:
        {
          Assert(stats.alpha_bar > 0., dealii::ExcInternalError());
          const GradientNorms n =
            set.reduced_gradient_norms(x, g, stats.alpha_bar);
          return std::sqrt(n.free_sq + n.reduced_chopped_sq);
        }
      }
      return 0.;
    }


    template <typename VectorType>
    bool
    SolverBase<VectorType>::check_stop(SolverStatistics &stats,
                                       const double      value,
                                       const double      cost)
    {
      // a relative cost decrease above this counts as progress: well
      // above the rounding of a cost kept by recurrences (1e-16 per step)
      constexpr double cost_progress = 1e-12;
      const double     relative      = value / stats.norm_b;
      stats.record_criterion(relative, timer.wall_time());
      stats.final_criterion = relative;
      report_progress(stats);
      if (!std::isfinite(relative))
      {
        stats.reason  = ConvergenceReason::non_finite;
        stats.message = "the stopping criterion became " + sci(relative);
        return true;
      }
      if (relative <= prm.tolerance)
      {
        stats.reason = ConvergenceReason::converged;
        return true;
      }
      bool progress = false;
      if (relative < best_criterion)
      {
        best_criterion = relative;
        progress       = true;
      }
      if (std::isfinite(cost) &&
          (cost_at_progress == std::numeric_limits<double>::infinity() ||
           cost_at_progress - cost >
             cost_progress *
               std::max(std::abs(cost_at_progress), std::abs(cost))))
        progress = true;
      if (progress)
      {
        progress_iteration = stats.iterations;
        // the least cost seen at a progress: the same as the last cost
        // for the monotone solvers, and for the non-monotone ones (SPG-QP,
        // PBBf) a rise and fall back is not progress
        if (std::isfinite(cost))
          cost_at_progress = std::min(cost_at_progress, cost);
      }
      if (stats.iterations >= prm.max_iterations)
      {
        stats.reason = ConvergenceReason::max_iterations;
        stats.message =
          "iteration limit " + std::to_string(prm.max_iterations) + " reached";
        return true;
      }
      if (prm.stagnation_window > 0 &&
          stats.iterations - progress_iteration >= prm.stagnation_window)
      {
        stats.reason = ConvergenceReason::stagnation;
        stats.message =
          "no progress for " + std::to_string(prm.stagnation_window) +
          " iterations: no new minimum of the criterion (best " +
          sci(best_criterion) + ")" +
          (std::isfinite(cost) ?
             " and the cost fell by at most a relative " + sci(cost_progress) :
             std::string());
        return true;
      }
      return false;
    }


    template <typename VectorType>
    void
    SolverBase<VectorType>::report_progress(const SolverStatistics &stats)
    {
      if (!prm.progress)
        return;
      const double now = timer.wall_time();
      if (now < next_report_time)
        return;
      ProgressReport report;
      report.solver             = solver_name;
      report.first              = next_report_time == 0.;
      report.iterations         = stats.iterations;
      report.n_hessian_products = stats.n_hessian_products;
      report.criterion          = stats.final_criterion;
      report.tolerance          = prm.tolerance;
      report.elapsed            = now;
      // counting the active blocks of distributed vectors is a reduction,
      // and the processes report at different times
      if constexpr (std::is_same_v<VectorType, dealii::Vector<double>>)
        if (progress_problem != nullptr && progress_problem->constraints &&
            progress_x != nullptr)
        {
          const auto &set = *progress_problem->constraints;
          report.n_blocks = set.n_blocks();
          report.n_active = 0;
          for (const auto n : set.n_active_blocks(*progress_x))
            report.n_active += n;
        }
      prm.progress.report(report);
      next_report_time = now + std::max(prm.progress.interval, 1e-9);
    }


    template <typename VectorType>
    double
    SolverBase<VectorType>::elapsed() const
    {
      return timer.wall_time();
    }


    template <typename VectorType>
    void
    SolverBase<VectorType>::finish(const Problem<VectorType> &problem,
                                   const VectorType          &x,
                                   SolverStatistics          &stats)
    {
      // time first: the KKT report costs a product that is not the
      // solver's work
      stats.wall_time = timer.wall_time();
      stats.kkt       = compute_kkt_residuals(problem, x);
    }


    template class SolverBase<dealii::Vector<double>>;
    template class SolverBase<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
