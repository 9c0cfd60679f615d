#include <contact/contact_solver.h>
#include <qp/solver_factory.h>

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace dualcontact
{
  namespace contact
  {
    std::string
    undetermined_rigid_body_motion()
    {
      return " (the multipliers leave the rigid-body motion of a floating "
             "body undetermined: set to zero)";
    }


    template <int dim>
    ContactSolver<dim>::ContactSolver(
      DualFormulation<dim>        &dual,
      const qp::SolverParameters  &qp_parameters,
      const qp::SMALSEMParameters &smalse_parameters,
      const CoulombParameters     &coulomb_parameters,
      const WorkingSetParameters  &working_set_parameters)
        : dual_(dual)
        , qp_parameters_(qp_parameters)
        , smalse_parameters_(smalse_parameters)
        , coulomb_parameters_(coulomb_parameters)
        , working_set_parameters_(working_set_parameters)
    {
    }


    namespace
    {
      using Replicated  = dealii::Vector<double>;
      using Distributed = dealii::TrilinosWrappers::MPI::Vector;

      template <int dim>
      qp::Problem<Replicated>
      make_problem(const DualFormulation<dim> &dual, const Replicated &)
      {
        return dual.make_problem();
      }

      template <int dim>
      qp::Problem<Distributed>
      make_problem(const DualFormulation<dim> &dual, const Distributed &)
      {
        return dual.make_distributed_problem();
      }

      template <int dim>
      void
      update_bounds(DualFormulation<dim> &dual, const Replicated &lambda)
      {
        dual.update_slip_bounds(&lambda);
      }

      template <int dim>
      void
      update_bounds(DualFormulation<dim> &dual, const Distributed &lambda)
      {
        dual.update_slip_bounds(lambda);
      }

      /** Result::lambda: the whole vector (gathered if distributed). */
      template <int dim>
      void
      whole(const DualFormulation<dim> &, const Replicated &v, Replicated &out)
      {
        out = v;
      }

      template <int dim>
      void
      whole(const DualFormulation<dim> &dual,
            const Distributed          &v,
            Replicated                 &out)
      {
        dual.gather(v, out);
      }
    } // namespace


    template <int dim>
    template <typename V>
    qp::SolverStatistics
    ContactSolver<dim>::run_solver(const qp::Problem<V> &problem,
                                   V                    &lambda,
                                   const double          tolerance) const
    {
      qp::SolverParameters parameters = qp_parameters_;
      if (tolerance > 0.)
        parameters.tolerance = tolerance;
      return qp::make_solver<V>(parameters, smalse_parameters_, problem)
        ->solve(problem, lambda);
    }


    template <int dim>
    void
    ContactSolver<dim>::set_initial_multipliers(
      const dealii::Vector<double> &lambda)
    {
      initial_multipliers_ = lambda;
    }


    template <int dim>
    void
    ContactSolver<dim>::set_final_recovery(const bool recover)
    {
      final_recovery_ = recover;
    }


    template <int dim>
    void
    ContactSolver<dim>::set_coulomb_monitor(
      std::function<void(const Result &)> monitor)
    {
      coulomb_monitor_ = std::move(monitor);
    }


    template <int dim>
    template <typename V>
    qp::SolverStatistics
    ContactSolver<dim>::solve_qp(V &lambda, WorkingSetRecord &record) const
    {
      if constexpr (std::is_same_v<V, Replicated>)
        return solve_on_working_set(lambda, record);
      record = WorkingSetRecord();
      return run_solver(make_problem(dual_, lambda), lambda);
    }


    namespace
    {
      /** @p total with the work of @p next added, and @p next's outcome. */
      qp::SolverStatistics
      accumulate(const qp::SolverStatistics &total, qp::SolverStatistics next)
      {
        next.iterations += total.iterations;
        next.n_outer += total.n_outer;
        next.n_hessian_products += total.n_hessian_products;
        next.n_projections += total.n_projections;
        next.wall_time += total.wall_time;
        return next;
      }
    } // namespace


    template <int dim>
    qp::SolverStatistics
    ContactSolver<dim>::solve_on_working_set(Replicated       &lambda,
                                             WorkingSetRecord &record) const
    {
      const qp::Problem<Replicated> full = dual_.make_problem();
      WorkingSet<dim> working_set(dual_, full, working_set_parameters_);
      if (!working_set.drops_rows() && !working_set.separates_rows())
      {
        record = working_set.record();
        return run_solver(full, lambda);
      }

      // with separated rows to find, the rounds start at the separation
      // tolerance and tighten towards the QP's own (see WorkingSet)
      const double final_tolerance = qp_parameters_.tolerance;
      double       tolerance       = final_tolerance;
      if (working_set.separates_rows())
        tolerance = std::max(final_tolerance,
                             working_set_parameters_.separation_tolerance);
      qp::SolverStatistics                total;
      std::vector<dealii::Vector<double>> displacements;
      for (;;)
      {
        Replicated kept;
        working_set.gather(lambda, kept);
        const qp::SolverStatistics round =
          run_solver(working_set.reduced_problem(), kept, tolerance);
        total =
          working_set.record().n_rounds == 0 ? round : accumulate(total, round);
        ++working_set.record().n_rounds;
        working_set.scatter(kept, lambda);
        if (!round.converged())
          working_set.record().fall_back =
            "the QP on the working set did not converge (" +
            qp::to_string(round.reason) + ")";
        else if (!dual_.recover(lambda, displacements, false))
          working_set.record().fall_back =
            "the working set leaves a rigid-body motion undetermined";
        else if (const unsigned int added =
                   working_set.add_violated_rows(displacements);
                 tolerance > final_tolerance)
        {
          // a round of the tolerance ladder: the rows it finds separated
          // leave, the next round is tighter; once a round that moved finds
          // no row to drop or add, the next round is the last
          const unsigned int dropped =
            working_set.drop_separated_rows(lambda, displacements);
          tolerance *= working_set_parameters_.separation_reduction;
          if ((round.iterations > 0 && dropped == 0 && added == 0 &&
               working_set.record().n_separated > 0) ||
              tolerance < (1. + 1e-6) * final_tolerance)
            tolerance = final_tolerance;
        }
        else if (added == 0)
          break;
        if (working_set.record().fall_back.empty() &&
            working_set.record().n_rounds >= working_set_parameters_.max_rounds)
          working_set.record().fall_back =
            "rows still added back after " +
            std::to_string(working_set.record().n_rounds) + " rounds";
        if (!working_set.record().fall_back.empty())
        {
          // all rows, warm started: never worse than without the set
          total = accumulate(total, run_solver(full, lambda));
          working_set.record().n_dropped_final = 0;
          break;
        }
      }
      record = working_set.record();
      return total;
    }


    template <int dim>
    typename ContactSolver<dim>::Result
    ContactSolver<dim>::solve(
      const std::function<void(const Result &)> &on_iterate)
    {
      if (dual_.is_distributed())
        return solve_on<Distributed>(on_iterate);
      return solve_on<Replicated>(on_iterate);
    }


    template <int dim>
    template <typename V>
    typename ContactSolver<dim>::Result
    ContactSolver<dim>::solve_on(
      const std::function<void(const Result &)> &on_iterate)
    {
      Result result;
      V      lambda;
      if constexpr (std::is_same_v<V, Distributed>)
      {
        dual_.initialize_multipliers(lambda);
        result.qp_vectors = "dealii::TrilinosWrappers::MPI::Vector";
        result.multipliers_per_process =
          dealii::Utilities::MPI::all_gather(lambda.get_mpi_communicator(),
                                             static_cast<unsigned int>(
                                               lambda.locally_owned_size()));
      }
      else
      {
        lambda.reinit(dual_.n_multipliers());
        result.qp_vectors              = "dealii::Vector<double>";
        result.multipliers_per_process = {
          static_cast<unsigned int>(lambda.size())};
      }
      // the first Coulomb iterate is bonded, also when warm started: the
      // bounds of the previous step's normal multipliers can be too small
      // for the new load of a floating body (an infeasible Tresca QP)
      dual_.update_slip_bounds(nullptr);
      if (initial_multipliers_.size() == dual_.n_multipliers())
      {
        // a warm start: the previous load step's multipliers
        if constexpr (std::is_same_v<V, Distributed>)
        {
          for (const auto i : lambda.locally_owned_elements())
            lambda(i) = initial_multipliers_(i);
          lambda.compress(dealii::VectorOperation::insert);
        }
        else
          lambda = initial_multipliers_;
      }

      const bool has_coulomb = dual_.has_coulomb_friction();

      result.working_sets.emplace_back();
      result.qp_statistics.push_back(
        solve_qp(lambda, result.working_sets.back()));
      if (!result.qp_statistics.back().converged())
      {
        result.reason = "QP solver did not converge: " +
                        qp::to_string(result.qp_statistics.back().reason);
        whole(dual_, lambda, result.lambda);
        if (final_recovery_ &&
            !dual_.recover(lambda, result.displacements, false))
          result.reason += undetermined_rigid_body_motion();
        return result;
      }

      if (has_coulomb)
      {
        CoulombFixedPoint fixed_point(coulomb_parameters_);
        for (unsigned int it = 0;; ++it)
        {
          const std::vector<double> old_first  = dual_.slip_bounds_first();
          const std::vector<double> old_second = dual_.slip_bounds_second();
          update_bounds(dual_, lambda);
          double change = 0, norm = 0;
          bool   from_bonded = false;
          for (unsigned int j = 0; j < old_first.size(); ++j)
          {
            // the first iterate was bonded (infinite bounds) on Coulomb
            // pairs: its change is not a number to compare
            if (std::isinf(old_first[j]) || std::isinf(old_second[j]))
            {
              from_bonded = true;
              continue;
            }
            change +=
              std::pow(dual_.slip_bounds_first()[j] - old_first[j], 2) +
              std::pow(dual_.slip_bounds_second()[j] - old_second[j], 2);
            norm += std::pow(dual_.slip_bounds_first()[j], 2) +
                    std::pow(dual_.slip_bounds_second()[j], 2);
          }
          const CoulombFixedPoint::State state = fixed_point.record_change(
            from_bonded ? 1. :
                          CoulombFixedPoint::relative_change(change, norm));
          result.coulomb_changes = fixed_point.changes();
          if (coulomb_monitor_)
            coulomb_monitor_(result);
          if (on_iterate)
          {
            whole(dual_, lambda, result.lambda);
            dual_.recover(lambda, result.displacements, false);
            on_iterate(result);
          }
          if (state != CoulombFixedPoint::State::iterating)
          {
            result.converged = state == CoulombFixedPoint::State::converged;
            result.reason    = fixed_point.message();
            break;
          }
          result.working_sets.emplace_back();
          result.qp_statistics.push_back(
            solve_qp(lambda, result.working_sets.back()));
          if (!result.qp_statistics.back().converged())
          {
            result.reason = "QP solver did not converge in Coulomb iteration " +
                            std::to_string(it + 1) + ": " +
                            qp::to_string(result.qp_statistics.back().reason);
            break;
          }
        }
      }
      else
        result.converged = true;

      if (result.converged)
        result.reason = "converged";
      whole(dual_, lambda, result.lambda);
      if (final_recovery_ &&
          !dual_.recover(lambda, result.displacements, result.converged))
        result.reason += undetermined_rigid_body_motion();
      return result;
    }


    template class ContactSolver<2>;
    template class ContactSolver<3>;
  } // namespace contact
} // namespace dualcontact
