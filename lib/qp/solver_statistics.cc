#include <qp/solver_statistics.h>

#include <deal.II/base/exceptions.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

namespace dualcontact
{
  namespace qp
  {
    std::string
    to_string(const ConvergenceReason reason)
    {
      return convergence_reason_names.name(reason);
    }


    void
    SolverStatistics::add_step_counts(const SolverStatistics &inner)
    {
      iterations += inner.iterations;
      n_cg += inner.n_cg;
      n_half_steps += inner.n_half_steps;
      n_expansions += inner.n_expansions;
      n_proportioning += inner.n_proportioning;
      n_bb += inner.n_bb;
      n_fall_back += inner.n_fall_back;
      n_preconditioned_releases += inner.n_preconditioned_releases;
      n_projections += inner.n_projections;
      n_preconditioner_setups += inner.n_preconditioner_setups;
      preconditioner_setup_time += inner.preconditioner_setup_time;
      n_preconditioner_applications += inner.n_preconditioner_applications;
      preconditioner_apply_time += inner.preconditioner_apply_time;
    }


    bool
    SolverStatistics::converged() const
    {
      return reason == ConvergenceReason::converged &&
             std::isfinite(final_criterion) && final_criterion <= tolerance;
    }


    void
    SolverStatistics::record_criterion(const double relative,
                                       const double seconds)
    {
      history.push_back(relative);
      history_time.push_back(seconds);
      history_iterations.push_back(iterations);
      history_products.push_back(n_hessian_products);
    }


    void
    SolverStatistics::drop_last_criterion()
    {
      Assert(!history.empty() && history_time.size() == history.size() &&
               history_iterations.size() == history.size() &&
               history_products.size() == history.size(),
             dealii::ExcInternalError());
      history.pop_back();
      history_time.pop_back();
      history_iterations.pop_back();
      history_products.pop_back();
    }


    nlohmann::json
    json_number(const double value)
    {
      if (std::isfinite(value))
        return value;
      std::ostringstream s;
      s << value;
      return s.str();
    }


    void
    SolverStatistics::write_json(std::ostream &out,
                                 const bool    with_history) const
    {
      nlohmann::json j;
      j["solver"]             = solver;
      j["stopping_criterion"] = stopping_criterion;
      j["tolerance"]          = json_number(tolerance);
      j["reason"]             = to_string(reason);
      j["converged"]          = converged();
      if (!message.empty())
        j["message"] = message;
      if (!settings.empty())
        j["settings"] = settings;
      j["iterations"]         = iterations;
      j["iterations_by_kind"] = {{"cg", n_cg},
                                 {"half_step", n_half_steps},
                                 {"expansion", n_expansions},
                                 {"proportioning", n_proportioning},
                                 {"bb", n_bb},
                                 {"fall_back", n_fall_back},
                                 {"preconditioned_release",
                                  n_preconditioned_releases},
                                 {"outer", n_outer}};
      j["hessian_products"]   = n_hessian_products;
      j["projections"]        = n_projections;
      j["preconditioner"]     = {
            {"setups", n_preconditioner_setups},
            {"setup_time", json_number(preconditioner_setup_time)},
            {"applications", n_preconditioner_applications},
            {"apply_time", json_number(preconditioner_apply_time)}};
      j["wall_time"]       = json_number(wall_time);
      j["norm_b"]          = json_number(norm_b);
      j["lambda_max"]      = json_number(lambda_max);
      j["alpha_bar"]       = json_number(alpha_bar);
      j["final_criterion"] = json_number(final_criterion);
      j["kkt"]             = {{"stationarity", json_number(kkt.stationarity)},
                              {"feasibility", json_number(kkt.feasibility)},
                              {"complementarity", json_number(kkt.complementarity)}};
      if (!attempts.empty())
      {
        nlohmann::json a = nlohmann::json::array();
        for (const SolverStatistics &attempt : attempts)
          a.push_back(nlohmann::json::parse(attempt.to_json(false)));
        j["attempts"]       = a;
        j["chosen_attempt"] = chosen_attempt;
        j["chosen_solver"] =
          chosen_attempt >= 0 &&
              chosen_attempt < static_cast<int>(attempts.size()) ?
            attempts[chosen_attempt].solver :
            std::string();
      }
      if (with_history)
      {
        nlohmann::json h = nlohmann::json::array();
        for (const double v : history)
          h.push_back(json_number(v));
        j["history"] = h;
        // the time stamps etc. exist only where the history was recorded
        // through record_criterion(); a record filled by hand may lack them
        if (history_time.size() == history.size())
        {
          j["history_time_s"]     = history_time;
          j["history_iterations"] = history_iterations;
          j["history_products"]   = history_products;
        }
      }
      out << j.dump(2);
    }


    std::string
    SolverStatistics::to_json(const bool with_history) const
    {
      std::ostringstream s;
      write_json(s, with_history);
      return s.str();
    }
  } // namespace qp
} // namespace dualcontact
