#include <qp/solver_chain.h>
#include <qp/solver_factory.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <cmath>
#include <sstream>

namespace dualcontact
{
  namespace qp
  {
    namespace
    {
      /// Does @p problem have constraints and unknowns outside their
      /// blocks (TFETI's gluing and Dirichlet multipliers)?
      template <typename VectorType>
      bool
      has_unconstrained_unknowns(const Problem<VectorType> &problem)
      {
        return problem.constraints != nullptr &&
               problem.constraints->n_constrained_unknowns() < problem.b.size();
      }
    } // namespace


    template <typename VectorType>
    SolverChain<VectorType>::SolverChain(
      const SolverParameters  &parameters,
      const SMALSEMParameters &smalse_parameters)
        : SolverBase<VectorType>("auto", parameters)
        , smalse_prm(smalse_parameters)
    {
      parameters.check();
      smalse_prm.check();
    }


    template <typename VectorType>
    std::vector<std::string>
    SolverChain<VectorType>::chain(const Problem<VectorType> &problem) const
    {
      const bool general = problem.constraints != nullptr &&
                           !problem.constraints->only_bounds_and_boxes();
      return this->prm.auto_chain.chain(general);
    }


    template <typename VectorType>
    SolverParameters
    SolverChain<VectorType>::attempt_parameters(
      const Problem<VectorType> &problem,
      const std::string         &name) const
    {
      SolverParameters parameters = this->prm;
      parameters.solver           = name;
      if (this->prm.auto_chain.settings != "measured")
        return parameters;
      // settings the user chose win: the measured ones replace only the
      // thesis' table-14 values
      const SolverParameters thesis;
      const bool             chosen_by_user =
        parameters.gamma != thesis.gamma ||
        parameters.expansion != thesis.expansion ||
        parameters.projected_cg_trials != thesis.projected_cg_trials ||
        parameters.projected_cg_gradient_factor !=
          thesis.projected_cg_gradient_factor ||
        parameters.preconditioner != thesis.preconditioner ||
        parameters.proportioning_step != thesis.proportioning_step;
      if (chosen_by_user)
      {
        parameters.auto_chain.settings = "given";
        return parameters;
      }
      if (name == "mprgp" && problem.equality == nullptr &&
          problem.hessian_storage == HessianStorage::sparse_matrix)
      {
        // PERMON's best MPGP setting, and ours without a preconditioner
        // (doc/benchmarks/membrane.md, parts 2 and "Defaults (issue 20)")
        parameters.gamma     = 2.;
        parameters.expansion = "projected-cg";
        if (problem.free_set_preconditioner)
        {
          // the AMG in face with the trials that keep its whole step from
          // over-activating, and the preconditioned release
          parameters.projected_cg_trials          = 8;
          parameters.projected_cg_gradient_factor = 1.25;
          parameters.preconditioner               = "amg";
          parameters.proportioning_step           = "preconditioned";
        }
      }
      else if ((name == "mpgp-bb" || name == "mpgp") &&
               has_unconstrained_unknowns(problem))
      {
        // TFETI's dual: its gluing and Dirichlet multipliers are free, and
        // the CG steps they drive are cut short by the first contact block
        // near its boundary; the whole step projected moves them on and
        // activates those blocks at once (doc/benchmarks/tfeti.md,
        // "Projected-CG expansion on TFETI")
        parameters.expansion = "projected-cg";
        if (name == "mpgp-bb")
          parameters.gamma = 2.;
      }
      return parameters;
    }


    template <typename VectorType>
    std::string
    SolverChain<VectorType>::describe_settings(
      const SolverParameters &parameters)
    {
      std::ostringstream s;
      s << parameters.auto_chain.settings << ":";
      const std::string &name = parameters.solver;
      if (name == "mprgp" || name == "mpgp" || name == "mpgp-bb")
        s << " gamma=" << parameters.gamma;
      if (name == "mprgp" || name == "mpgp" || name == "mpgp-bb")
      {
        s << ", expansion=" << parameters.expansion;
        if (parameters.expansion == "projected-cg")
          s << ", projected-cg-trials=" << parameters.projected_cg_trials
            << ", projected-cg-gradient-factor="
            << parameters.projected_cg_gradient_factor;
      }
      if (name == "mprgp")
        s << ", preconditioner=" << parameters.preconditioner
          << ", proportioning=" << parameters.proportioning_step;
      if (name != "mprgp" && name != "mpgp" && name != "mpgp-bb")
        s << " table 14";
      return s.str();
    }


    template <typename VectorType>
    const SolverParameters &
    SolverChain<VectorType>::chosen_parameters() const
    {
      return last_parameters;
    }


    template <typename VectorType>
    double
    SolverChain<VectorType>::equality_residual() const
    {
      return last_equality_residual;
    }


    template <typename VectorType>
    SolverStatistics
    SolverChain<VectorType>::solve(const Problem<VectorType> &problem,
                                   VectorType                &x)
    {
      dealii::Timer                  timer;
      const std::vector<std::string> names = chain(problem);
      const VectorType               initial_guess(x);
      std::vector<SolverStatistics>  attempts;
      last_equality_residual    = 0.;
      this->last_gradient_valid = false;
      // Problem::start_gradient belongs to the caller's start: a later
      // attempt starts elsewhere (warm from the failed iterate)
      Problem<VectorType>        cleared;
      const Problem<VectorType> *attempt_problem = &problem;

      for (unsigned int k = 0; k < names.size(); ++k)
      {
        if (k > 0)
        {
          // a finite iterate of a failed attempt is feasible after the next
          // solver's projection: start there (warm) or from the caller's
          // guess (cold, or after NaN/Inf)
          const bool finite = std::isfinite(x.l2_norm());
          if (!this->prm.auto_chain.warm_start || !finite)
            x = initial_guess;
        }
        if (k == 1 && problem.start_gradient)
        {
          cleared = problem;
          cleared.start_gradient.reset();
          attempt_problem = &cleared;
        }
        const SolverParameters parameters =
          attempt_parameters(problem, names[k]);
        last_parameters = parameters;
        if (problem.equality)
        {
          SMALSEM<VectorType> smalse(parameters, smalse_prm);
          attempts.push_back(smalse.solve(*attempt_problem, x));
          attempts.back().settings  = describe_settings(parameters);
          last_equality_residual    = smalse.equality_residual();
          this->last_gradient_valid = false;
        }
        else
        {
          auto solver = create<VectorType>(names[k], parameters);
          attempts.push_back(solver->solve(*attempt_problem, x));
          attempts.back().settings = describe_settings(parameters);
          // the returned iterate's gradient, if its solver ended with it
          const VectorType *gradient = solver->final_gradient();
          this->last_gradient_valid  = gradient != nullptr;
          if (gradient)
          {
            this->last_gradient.reinit(*gradient, true);
            this->last_gradient.equ(1., *gradient);
          }
        }
        if (attempts.back().converged())
          break;
      }

      // the record of the returned iterate, with the work of all attempts
      SolverStatistics stats = attempts.back();
      stats.solver           = this->name();
      stats.iterations = stats.n_cg = stats.n_half_steps = stats.n_expansions =
        stats.n_proportioning = stats.n_bb = stats.n_fall_back = stats.n_outer =
          0;
      stats.n_preconditioned_releases = 0;
      stats.n_hessian_products = stats.n_projections = 0;
      stats.n_preconditioner_setups                  = 0;
      stats.n_preconditioner_applications            = 0;
      stats.preconditioner_setup_time = stats.preconditioner_apply_time = 0.;
      // the history runs through all attempts: each attempt's time stamps
      // and work counts are offset by those of the attempts before it, so a
      // convergence chart of `auto` shows the fall-back where it happened
      stats.history.clear();
      stats.history_time.clear();
      stats.history_iterations.clear();
      stats.history_products.clear();
      double      time_offset = 0.;
      std::string summary;
      for (const SolverStatistics &a : attempts)
      {
        const bool stamped = a.history_time.size() == a.history.size();
        for (unsigned int i = 0; i < a.history.size(); ++i)
        {
          stats.history.push_back(a.history[i]);
          stats.history_time.push_back(
            time_offset + (stamped ? a.history_time[i] : a.wall_time));
          stats.history_iterations.push_back(
            stats.iterations + (stamped ? a.history_iterations[i] : 0u));
          stats.history_products.push_back(
            stats.n_hessian_products + (stamped ? a.history_products[i] : 0ul));
        }
        time_offset += a.wall_time;
        stats.add_step_counts(a);
        stats.n_outer += a.n_outer;
        stats.n_hessian_products += a.n_hessian_products;
        summary += (summary.empty() ? "" : ", then ") + a.solver + " " +
                   to_string(a.reason);
      }
      stats.attempts       = attempts;
      stats.chosen_attempt = static_cast<int>(attempts.size()) - 1;
      stats.wall_time      = timer.wall_time();
      stats.message =
        "auto: " + summary +
        (stats.converged() ? "" : " (every solver of the chain failed)") +
        (attempts.back().message.empty() ?
           "" :
           "; last: " + attempts.back().message);
      return stats;
    }


    template class SolverChain<dealii::Vector<double>>;
    template class SolverChain<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
