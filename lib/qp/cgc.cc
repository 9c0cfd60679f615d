#include <qp/cgc.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace dualcontact
{
  namespace qp
  {
    namespace
    {
      using size_type = dealii::types::global_dof_index;

      // a serial vector needs no MPI (which may not even be initialised)
      bool
      on_one_process(const dealii::Vector<double> &)
      {
        return true;
      }

      bool
      on_one_process(const dealii::TrilinosWrappers::MPI::Vector &x)
      {
        return dealii::Utilities::MPI::n_mpi_processes(
                 x.get_mpi_communicator()) == 1;
      }

      void
      set_entries(dealii::Vector<double>       &x,
                  const std::vector<size_type> &index,
                  const std::vector<double>    &value)
      {
        for (std::size_t k = 0; k < index.size(); ++k)
          x(index[k]) = value[k];
      }

      void
      set_entries(dealii::TrilinosWrappers::MPI::Vector &x,
                  const std::vector<size_type>          &index,
                  const std::vector<double>             &value)
      {
        x.set(index, value);
        x.compress(dealii::VectorOperation::insert);
      }


      /**
       * State of one CGC solve: the problem, the iterate x, its gradient
       * r = Cx - b, the active set and the facet projection.  Keeping it
       * in one object lets subroutines CGC, CG and PROJECT of the report
       * be member functions that read like the report.
       */
      template <typename VectorType>
      class Run
      {
      public:
        using Data     = typename CGC<VectorType>::AdditionalData;
        using Operator = typename CGC<VectorType>::Operator;

        Run(const CGCProblem<VectorType> &problem,
            const Data                   &data,
            const Operator               &preconditioner,
            const Operator               &e_inverse,
            const Operator               &e_inverse_transpose,
            VectorType                   &x,
            SolverStatistics             &stats)
            : problem(problem)
            , rows(*problem.constraints)
            , data(data)
            , preconditioner(preconditioner)
            , e_inverse(e_inverse)
            , e_inverse_transpose(e_inverse_transpose)
            , x(x)
            , stats(stats)
            , in_facet(rows.n_rows(), 0)
        {
          r.reinit(x);
          p.reinit(x);
          Cp.reinit(x);
          Pr.reinit(x);
          z.reinit(x);
          t.reinit(x);
          orthogonal = rows.rows_orthogonal();
        }

        /// active rows at x
        std::vector<size_type>
        active_rows() const
        {
          std::vector<size_type> J;
          for (size_type i = 0; i < rows.n_rows(); ++i)
            if (is_active(i))
              J.push_back(i);
          return J;
        }

        bool
        is_active(const size_type i) const
        {
          const double ax = rows.row_dot(i, x);
          const double c  = rows.right_hand_side(i);
          // the scale of the rounding error of c - a_i'x: an active row
          // whose terms cancel (a_i'x = 0 from u_s = u_m) still has slack
          // of the size eps |a_ik x_k|, not eps |a_i'x|
          const double scale = std::abs(c) + rows.row_abs_dot(i, x);
          return c - ax <= data.active_tolerance * scale;
        }

        /**
         * Subroutine PROJECT: u = -(A_J A_J')^{-1} A_J v and
         * Pv = (I - P_J) v = v + A_J' u.
         */
        void
        project(const std::vector<size_type> &J,
                const VectorType             &v,
                std::vector<double>          &u,
                VectorType                   &Pv)
        {
          ++stats.n_projections;
          u.assign(J.size(), 0.);
          Pv = v;
          if (J.empty())
            return;
          std::vector<double> rhs(J.size());
          for (std::size_t k = 0; k < J.size(); ++k)
            rhs[k] = -rows.row_dot(J[k], v);
          if (orthogonal)
            for (std::size_t k = 0; k < J.size(); ++k)
              u[k] = rhs[k] / rows.row_norm_sq(J[k]);
          else
            solve_gram(J, rhs, u);
          rows.add_transpose(J, u, Pv);
        }

        /// CG with Jacobi preconditioning on (A_J A_J') u = rhs, matrix-
        /// free through a work vector of size n.
        void
        solve_gram(const std::vector<size_type> &J,
                   const std::vector<double>    &rhs,
                   std::vector<double>          &u)
        {
          const std::size_t   m = J.size();
          std::vector<double> res(rhs), d(m), q(m), s(m);
          const auto          gram =
            [&](const std::vector<double> &in, std::vector<double> &out)
          {
            t = 0.;
            rows.add_transpose(J, in, t);
            for (std::size_t k = 0; k < m; ++k)
              out[k] = rows.row_dot(J[k], t);
          };
          const auto dot =
            [](const std::vector<double> &a, const std::vector<double> &b)
          {
            double sum = 0.;
            for (std::size_t k = 0; k < a.size(); ++k)
              sum += a[k] * b[k];
            return sum;
          };
          const double norm_rhs = std::sqrt(dot(rhs, rhs));
          if (norm_rhs == 0.)
            return;
          for (std::size_t k = 0; k < m; ++k)
            s[k] = res[k] / rows.row_norm_sq(J[k]);
          d          = s;
          double rho = dot(res, s);
          for (unsigned int it = 0; it < data.projection_max_iterations; ++it)
          {
            gram(d, q);
            const double dq = dot(d, q);
            if (!(dq > 0.))
              break;
            const double alpha = rho / dq;
            for (std::size_t k = 0; k < m; ++k)
            {
              u[k] += alpha * d[k];
              res[k] -= alpha * q[k];
            }
            if (std::sqrt(dot(res, res)) <=
                data.projection_tolerance * norm_rhs)
              break;
            for (std::size_t k = 0; k < m; ++k)
              s[k] = res[k] / rows.row_norm_sq(J[k]);
            const double rho_new = dot(res, s);
            for (std::size_t k = 0; k < m; ++k)
              d[k] = s[k] + rho_new / rho * d[k];
            rho = rho_new;
          }
        }

        /// The criterion sqrt(||P_J r||^2 + sum min(u,0)^2 ||a||^2), and
        /// the multipliers of J in u.
        double
        criterion(const std::vector<size_type> &J,
                  std::vector<double>          &u,
                  double                       &norm_Pr,
                  double                       &norm_negative)
        {
          project(J, r, u, Pr);
          norm_Pr       = Pr.l2_norm();
          double neg_sq = 0.;
          for (std::size_t k = 0; k < J.size(); ++k)
            if (u[k] < 0.)
              neg_sq += u[k] * u[k] * rows.row_norm_sq(J[k]);
          norm_negative = std::sqrt(neg_sq);
          return std::sqrt(norm_Pr * norm_Pr + neg_sq);
        }

        /// The preconditioned projected residual z and rho = (r, z).
        double
        preconditioned_direction(const std::vector<size_type> &J)
        {
          std::vector<double> u;
          if (e_inverse)
          {
            // PCG-2: g = P E^{-1} P r, z = P E^{-T} g, rho = (g, g)
            e_inverse(t, Pr);
            project(J, t, u, z); // z holds g for the moment
            const double rho = z * z;
            e_inverse_transpose(t, z);
            project(J, t, u, z);
            return rho;
          }
          if (preconditioner)
          {
            preconditioner(t, Pr);
            project(J, t, u, z);
            return Pr * z;
          }
          z = Pr;
          return Pr * Pr;
        }

        enum class CGExit
        {
          facet_solved,
          constraint_hit,
          small_step,
          iteration_limit,
          unbounded,
          breakdown
        };

        /**
         * Subroutine CG on the facet J: CG with the projected (and
         * preconditioned) gradient until ||P_J r|| <= tolerance, a new
         * constraint is hit, the relative step is below step_tolerance or
         * the iteration limit is reached.
         */
        CGExit
        cg(const std::vector<size_type> &J,
           const double                  tolerance,
           const double                  step_tolerance,
           const bool                    force_step)
        {
          std::fill(in_facet.begin(), in_facet.end(), 0);
          for (const auto j : J)
            in_facet[j] = 1;
          blocked_at_start  = false;
          hit_at_first_step = false;
          std::vector<double> u;
          double              rho_old = 0.;
          for (unsigned int k = 0;; ++k)
          {
            project(J, r, u, Pr);
            const double norm_Pr = Pr.l2_norm();
            // after leaving a facet at least one step is taken, else a
            // loose tolerance could accept the larger facet at once and
            // the same constraint would be released again and again
            if (norm_Pr <= tolerance && !(force_step && k == 0 && norm_Pr > 0.))
              return CGExit::facet_solved;
            if (stats.iterations >= data.max_iterations)
              return CGExit::iteration_limit;
            const double rho = preconditioned_direction(J);
            if (!(rho > 0.) || !std::isfinite(rho))
            {
              stats.message = "preconditioned residual norm " +
                              std::to_string(rho) +
                              " (preconditioner not positive definite?)";
              return CGExit::breakdown;
            }
            if (k == 0)
            {
              p = z;
              p *= -1.;
            }
            else
            {
              p.sadd(rho / rho_old, -1., z);
              // the recurrence lets rounding (and the finite accuracy
              // of the Gram solve) push p out of the facet's null
              // space; over many steps x would drift across the facet
              // constraints, so p is projected back (cheap next to a
              // Hessian product, exact for orthogonal rows)
              if (!J.empty())
              {
                t = p;
                project(J, t, u, p);
              }
            }
            rho_old = rho;

            problem.hessian(Cp, p);
            ++stats.n_hessian_products;
            ++stats.iterations;
            const double pCp = p * Cp;
            const double rp  = r * p;
            if (!std::isfinite(pCp) || !std::isfinite(rp))
            {
              stats.message = "non-finite p'Cp or r'p";
              return CGExit::breakdown;
            }
            const double alpha =
              pCp > 0. ? -rp / pCp : std::numeric_limits<double>::infinity();

            // largest feasible step along p over rows not in the facet
            double                 alpha_max = alpha;
            std::vector<size_type> blocking;
            for (size_type i = 0; i < rows.n_rows(); ++i)
              if (!in_facet[i])
              {
                const double ap = rows.row_dot(i, p);
                if (ap > 0.)
                {
                  const double step = std::max(0., rows.slack(i, x)) / ap;
                  if (step < alpha_max)
                  {
                    alpha_max = step;
                    blocking.assign(1, i);
                  }
                  else if (step == alpha_max && !blocking.empty())
                    blocking.push_back(i);
                }
              }
            if (!blocking.empty())
            {
              blocked_at_start  = k == 0 && alpha_max == 0.;
              hit_at_first_step = k == 0;
              x.add(alpha_max, p);
              r.add(alpha_max, Cp);
              // put single-entry rows (bounds) exactly on the bound so
              // that the active test does not depend on rounding
              std::vector<size_type> index;
              std::vector<double>    value;
              for (const auto i : blocking)
                if (rows.row_length(i) == 1)
                {
                  index.push_back(rows.first_column(i));
                  value.push_back(rows.right_hand_side(i) /
                                  rows.first_value(i));
                }
              if (!index.empty())
                set_entries(x, index, value);
              ++stats.n_half_steps;
              return CGExit::constraint_hit;
            }
            if (!std::isfinite(alpha))
            {
              stats.message = "p'Cp <= 0 and no constraint blocks the "
                              "direction: the cost is unbounded below";
              return CGExit::unbounded;
            }
            x.add(alpha, p);
            r.add(alpha, Cp);
            ++stats.n_cg;
            const double dd = alpha * p.l2_norm() / std::max(1., x.l2_norm());
            if (dd < step_tolerance)
              return CGExit::small_step;
          }
        }

        const CGCProblem<VectorType> &problem;
        const LinearInequalities     &rows;
        const Data                   &data;
        const Operator               &preconditioner;
        const Operator               &e_inverse;
        const Operator               &e_inverse_transpose;
        VectorType                   &x;
        SolverStatistics             &stats;
        VectorType                    r, p, Cp, Pr, z, t;
        std::vector<char>             in_facet;
        bool                          orthogonal = false;
        /// the last cg() stopped at its first step with step length 0 (a
        /// row outside the facet, active at x, blocks the first direction)
        bool blocked_at_start = false;
        /// the last cg() hit a row outside the facet in its first step
        bool hit_at_first_step = false;
      };
    } // namespace


    template <typename VectorType>
    CGC<VectorType>::CGC(const AdditionalData &data)
        : data(data)
    {
      AssertThrow(data.tolerance > 0. && data.loose_tolerance > 0. &&
                    data.strict_factor > 0. && data.strict_factor <= 1. &&
                    data.active_tolerance >= 0.,
                  dealii::ExcMessage("CGC: tolerances must be positive and "
                                     "the strict factor in (0, 1]"));
    }


    template <typename VectorType>
    void
    CGC<VectorType>::set_preconditioner(const Operator &apply_inverse)
    {
      clear_preconditioner();
      preconditioner = apply_inverse;
    }


    template <typename VectorType>
    void
    CGC<VectorType>::set_split_preconditioner(
      const Operator &apply_E_inverse,
      const Operator &apply_E_inverse_transpose)
    {
      AssertThrow(apply_E_inverse && apply_E_inverse_transpose,
                  dealii::ExcMessage("CGC: both factors of a split "
                                     "preconditioner are needed"));
      clear_preconditioner();
      e_inverse           = apply_E_inverse;
      e_inverse_transpose = apply_E_inverse_transpose;
    }


    template <typename VectorType>
    void
    CGC<VectorType>::clear_preconditioner()
    {
      preconditioner      = Operator();
      e_inverse           = Operator();
      e_inverse_transpose = Operator();
    }


    template <typename VectorType>
    const std::vector<std::pair<typename CGC<VectorType>::size_type, double>> &
    CGC<VectorType>::multipliers() const
    {
      return final_multipliers;
    }


    template <typename VectorType>
    const std::vector<typename CGC<VectorType>::OuterRecord> &
    CGC<VectorType>::outer_log() const
    {
      return outer_records;
    }


    template <typename VectorType>
    SolverStatistics
    CGC<VectorType>::solve(const CGCProblem<VectorType> &problem, VectorType &x)
    {
      dealii::Timer timer;
      outer_records.clear();
      AssertThrow(static_cast<bool>(problem.hessian),
                  dealii::ExcMessage("CGC: the problem has no Hessian"));
      AssertThrow(problem.constraints != nullptr,
                  dealii::ExcMessage("CGC: the problem has no constraints "
                                     "(use CG for an unconstrained problem)"));
      AssertThrow(x.size() == problem.b.size(),
                  dealii::ExcMessage("CGC: x and b differ in size"));
      AssertThrow(problem.constraints->min_columns() <= x.size(),
                  dealii::ExcMessage(
                    "CGC: a constraint refers to unknown " +
                    std::to_string(problem.constraints->min_columns() - 1) +
                    " of a problem with " + std::to_string(x.size()) +
                    " unknowns"));
      AssertThrow(on_one_process(x),
                  dealii::ExcMessage("CGC runs on one process only (its "
                                     "constraint rows access entries by "
                                     "global index)"));
      const LinearInequalities &rows = *problem.constraints;

      SolverStatistics stats;
      stats.solver             = "cgc";
      stats.stopping_criterion = "projected";
      stats.tolerance          = data.tolerance;
      const double norm_b      = problem.b.l2_norm();
      AssertThrow(std::isfinite(norm_b),
                  dealii::ExcMessage("CGC: b is not finite"));
      stats.norm_b = norm_b > 0. ? norm_b : 1.;

      // a feasible start: enforce bounds, reject other violated rows
      {
        std::vector<size_type> index;
        std::vector<double>    value;
        for (size_type i = 0; i < rows.n_rows(); ++i)
          if (rows.row_length(i) == 1 && rows.slack(i, x) < 0.)
          {
            index.push_back(rows.first_column(i));
            value.push_back(rows.right_hand_side(i) / rows.first_value(i));
          }
        if (!index.empty())
          set_entries(x, index, value);
        for (size_type i = 0; i < rows.n_rows(); ++i)
        {
          const double s = rows.slack(i, x);
          if (!(s >= -1e-12 * (std::abs(rows.right_hand_side(i)) +
                               rows.row_abs_dot(i, x))))
          {
            std::ostringstream text;
            text << "CGC: the initial guess violates constraint " << i << " by "
                 << -s << " (CGC needs a feasible start)";
            AssertThrow(false, dealii::ExcMessage(text.str()));
          }
        }
      }

      Run<VectorType> run(problem,
                          data,
                          preconditioner,
                          e_inverse,
                          e_inverse_transpose,
                          x,
                          stats);
      problem.hessian(run.r, x);
      ++stats.n_hessian_products;
      run.r -= problem.b;

      const bool   report = data.stopping_test == StoppingTest::report;
      const double absolute_tolerance = data.tolerance * stats.norm_b;
      const double strict             = data.strict_factor * absolute_tolerance;
      const double loose =
        std::max(data.loose_tolerance * stats.norm_b, absolute_tolerance);
      // the report's epsilon of this outer iteration (remark 7.3)
      const auto report_epsilon = [&](const bool loose_phase)
      { return loose_phase ? data.loose_tolerance : data.tolerance; };
      const bool release_all =
        data.release == Release::all_negative ||
        (data.release == Release::automatic && run.orthogonal);

      // Lemma 7.2 holds for mutually orthogonal rows and no
      // preconditioning; with a preconditioner (or rows that are not
      // orthogonal) a released row may block the first direction at once
      // (step length 0), and releasing the same rows again would cycle.
      // Then the next release at this point drops the most negative
      // multiplier only (lemma 7.1), whatever the rule.
      bool                   release_one_next = false;
      double                 best = std::numeric_limits<double>::infinity();
      unsigned int           best_iteration = 0;
      bool                   strict_phase   = false;
      unsigned int           idle_outer     = 0;
      double                 pg_previous    = 0.; // remark 7.2's pg^{IT}
      bool                   cg_finished    = false;
      std::vector<double>    u;
      std::vector<size_type> J;
      for (unsigned int outer = 0;; ++outer)
      {
        J                    = run.active_rows();
        double       norm_Pr = 0., norm_negative = 0.;
        const double value = run.criterion(J, u, norm_Pr, norm_negative);
        stats.record_criterion(value / stats.norm_b, timer.wall_time());
        stats.final_criterion = value / stats.norm_b;
        if (!std::isfinite(value))
        {
          stats.reason  = ConvergenceReason::non_finite;
          stats.message = "the criterion became " + std::to_string(value);
          break;
        }
        const bool loose_phase = !strict_phase && outer < data.n_loose;
        // the facet problem solved and the multipliers that count as
        // negative, by the test in use
        bool              facet_solved = false;
        std::vector<char> negative(J.size(), 0);
        bool              any_negative = false;
        if (report)
        {
          const double epsilon = report_epsilon(loose_phase);
          // As printed the tests can disagree: CG returns at once when
          // ||(I - P_J) g||^2 < epsilon while pg / max(1, pg^{IT}) stays
          // above epsilon, and CGC would call it again forever.  A
          // facet on which CG has just stopped by its own tests counts as
          // solved too.
          facet_solved =
            norm_Pr / std::max(1., pg_previous) < epsilon || cg_finished;
          pg_previous    = norm_Pr;
          double u_scale = 1.;
          for (const double u_k : u)
            u_scale = std::max(u_scale, u_k);
          for (std::size_t k = 0; k < J.size(); ++k)
          {
            negative[k]  = u[k] / u_scale < -epsilon;
            any_negative = any_negative || negative[k];
          }
          if (facet_solved && !any_negative && epsilon <= data.tolerance)
          {
            // the report's epsilon is no bound on the criterion relative
            // to ||b||: the record states the one reached
            stats.tolerance = std::max(stats.tolerance, value / stats.norm_b);
            stats.reason    = ConvergenceReason::converged;
            break;
          }
        }
        else
        {
          if (value <= absolute_tolerance)
          {
            stats.reason = ConvergenceReason::converged;
            break;
          }
          facet_solved = norm_Pr <= (loose_phase ? loose : strict);
          for (std::size_t k = 0; k < J.size(); ++k)
            negative[k] = u[k] < 0.;
          any_negative = norm_negative > 0.5 * absolute_tolerance;
        }
        if (stats.iterations >= data.max_iterations)
        {
          stats.reason  = ConvergenceReason::max_iterations;
          stats.message = "iteration limit " +
                          std::to_string(data.max_iterations) + " reached";
          break;
        }
        if (value < best)
        {
          best           = value;
          best_iteration = stats.iterations;
        }
        else if (data.stagnation_window > 0 &&
                 stats.iterations - best_iteration >= data.stagnation_window)
        {
          stats.reason  = ConvergenceReason::stagnation;
          stats.message = "no new minimum of the criterion for " +
                          std::to_string(data.stagnation_window) + " CG steps";
          break;
        }
        ++stats.n_outer;

        bool                   strict_next = !loose_phase;
        std::vector<size_type> facet       = J;
        if (facet_solved)
        {
          if (any_negative)
          {
            // leave the facet of the negative multiplier(s)
            std::vector<size_type> kept;
            std::size_t            most_negative = 0;
            double                 most          = 0.;
            for (std::size_t k = 0; k < J.size(); ++k)
            {
              const double scaled = u[k] * std::sqrt(rows.row_norm_sq(J[k]));
              if (scaled < most)
              {
                most          = scaled;
                most_negative = k;
              }
            }
            for (std::size_t k = 0; k < J.size(); ++k)
            {
              const bool release = (release_all && !release_one_next) ?
                                     negative[k] :
                                     k == most_negative;
              if (!release)
                kept.push_back(J[k]);
            }
            facet = kept;
            ++stats.n_proportioning;
          }
          else
          {
            // facet solved only loosely and the multipliers are
            // fine: from now on solve facets strictly (remark 7.3)
            strict_phase = true;
            strict_next  = true;
          }
        }

        // the report's CG returns at ||(I - P_J) g||^2 < epsilon and
        // at a relative step below epsilon
        const double epsilon = report_epsilon(!strict_next);
        const double tolerance =
          report ? std::sqrt(epsilon) : (strict_next ? strict : loose);
        const double step_tolerance = report ? epsilon : data.step_tolerance;
        const unsigned int steps_before = stats.iterations;
        const auto         exit =
          run.cg(facet, tolerance, step_tolerance, facet.size() != J.size());
        // The report's multiplier test releases rows whose multipliers
        // are negative by round-off only; such rows block the next
        // direction after a step of round-off length and come back, and
        // releasing all of them again would cycle (measured on the bridge
        // at epsilon <= 1e-12): there a row hit in the first step counts
        // as blocking.
        // (kept over outer iterations without a release, which the
        // report's facet test may put in between)
        if (!report || facet.size() != J.size())
          release_one_next =
            J.size() - facet.size() > 1 &&
            (run.blocked_at_start || (report && run.hit_at_first_step));
        OuterRecord record;
        record.n_active         = J.size();
        record.n_facet          = facet.size();
        record.inner_iterations = stats.iterations - steps_before;
        outer_records.push_back(record);
        if (stats.iterations == steps_before)
        {
          // no step at all: the same state would come back
          if (++idle_outer >= 2)
          {
            stats.reason  = ConvergenceReason::stagnation;
            stats.message = "CGC made no step in two outer iterations";
            break;
          }
          strict_phase = true;
        }
        else
          idle_outer = 0;
        cg_finished = exit == Run<VectorType>::CGExit::facet_solved ||
                      exit == Run<VectorType>::CGExit::small_step;
        if (exit == Run<VectorType>::CGExit::unbounded)
        {
          stats.reason = ConvergenceReason::unbounded;
          break;
        }
        if (exit == Run<VectorType>::CGExit::breakdown)
        {
          stats.reason = ConvergenceReason::breakdown;
          break;
        }
      }

      stats.wall_time = timer.wall_time();
      // KKT residuals at the returned x (J, u are those of the last
      // criterion evaluation, i.e. of x)
      stats.kkt.stationarity = stats.final_criterion * stats.norm_b;
      double infeasible_sq = 0., complementarity = 0.;
      for (size_type i = 0; i < rows.n_rows(); ++i)
      {
        const double s = rows.slack(i, x);
        if (s < 0.)
          infeasible_sq += s * s;
      }
      final_multipliers.clear();
      for (std::size_t k = 0; k < J.size() && k < u.size(); ++k)
      {
        complementarity += std::abs(u[k]) * std::abs(rows.slack(J[k], x));
        final_multipliers.emplace_back(J[k], u[k]);
      }
      stats.kkt.feasibility     = std::sqrt(infeasible_sq);
      stats.kkt.complementarity = complementarity;
      return stats;
    }


    template class CGC<dealii::Vector<double>>;
    template class CGC<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
