#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <fclib/accuracy.h>
#include <fclib/local_solver.h>
#include <qp/power_iteration.h>
#include <qp/separable_set.h>
#include <qp/solver_factory.h>

#include <cmath>
#include <sstream>

namespace dualcontact
{
  namespace fclib
  {
    std::string
    to_string(const Model model)
    {
      return model == Model::cone ? "cone" : "coulomb";
    }


    Model
    parse_model(const std::string &name)
    {
      if (name == "coulomb")
        return Model::coulomb_fixed_point;
      if (name == "cone")
        return Model::cone;
      AssertThrow(false,
                  dealii::ExcMessage("unknown model `" + name +
                                     "' (coulomb | cone)"));
      return Model::cone;
    }


    std::string
    to_string(const FirstIterate first)
    {
      return first == FirstIterate::bonded ? "bonded" : "frictionless";
    }


    FirstIterate
    parse_first_iterate(const std::string &name)
    {
      if (name == "bonded")
        return FirstIterate::bonded;
      if (name == "frictionless")
        return FirstIterate::frictionless;
      AssertThrow(false,
                  dealii::ExcMessage("unknown first Coulomb iterate `" + name +
                                     "' (bonded | frictionless)"));
      return FirstIterate::bonded;
    }


    LocalSolver::LocalSolver(const LocalProblem               &problem,
                             const qp::SolverParameters       &qp_parameters,
                             const contact::CoulombParameters &coulomb,
                             const Model                       model,
                             const FirstIterate                first)
        : problem_(problem)
        , qp_parameters_(qp_parameters)
        , coulomb_parameters_(coulomb)
        , model_(model)
        , first_(first)
    {
      AssertThrow(model != Model::cone || problem.spacedim() == 3,
                  dealii::ExcMessage("the cone model needs a 3D problem (the "
                                     "cone block has 3 unknowns)"));
    }


    qp::SolverStatistics
    LocalSolver::solve_qp(dealii::Vector<double>    &r,
                          const std::vector<double> *psi,
                          const double               lambda_max) const
    {
      const unsigned int dim = problem_.spacedim();
      auto set = std::make_shared<qp::SeparableSet<dealii::Vector<double>>>();
      for (unsigned int i = 0; i < problem_.n_contacts(); ++i)
      {
        const unsigned int first = dim * i;
        const double       mu    = problem_.mu()[i];
        if (model_ == Model::cone)
        {
          set->add_cone(first, mu);
          continue;
        }
        set->add_bound(first, 0.);
        // psi == nullptr: bonded iterate, no bound on frictional contacts
        if (mu > 0 && psi == nullptr)
          continue;
        const double bound = mu > 0 ? (*psi)[i] : 0.;
        if (bound == 0.) // r_t = 0: boxes, which mprgp also takes
          for (unsigned int k = 1; k < dim; ++k)
            set->add_box(first + k, 0., 0.);
        else if (dim == 3)
          set->add_disc(first + 1, bound);
        else
          set->add_box(first + 1, -bound, bound);
      }
      set->finalize(r);

      qp::Problem<dealii::Vector<double>> qp;
      qp.hessian =
        [this](dealii::Vector<double> &dst, const dealii::Vector<double> &src)
      { problem_.symmetric_vmult(dst, src); };
      qp.b = problem_.q();
      qp.b *= -1.;
      qp.constraints  = set;
      qp.lambda_max   = lambda_max;
      qp.semidefinite = true;
      auto solver     = qp::create<dealii::Vector<double>>(qp_parameters_);
      return solver->solve(qp, r);
    }


    LocalSolver::Result
    LocalSolver::solve(dealii::Vector<double> &r) const
    {
      AssertThrow(r.size() == problem_.size(),
                  dealii::ExcMessage("LocalSolver: start vector of size " +
                                     std::to_string(r.size()) + ", expected " +
                                     std::to_string(problem_.size())));
      dealii::Timer      timer;
      Result             result;
      const unsigned int dim = problem_.spacedim();

      const auto power = qp::power_iteration<dealii::Vector<double>>(
        [this](dealii::Vector<double> &dst, const dealii::Vector<double> &src)
        { problem_.symmetric_vmult(dst, src); },
        problem_.q(),
        qp_parameters_.power_max_iterations,
        qp_parameters_.power_tolerance,
        qp_parameters_.power_safety_factor);
      result.hessian_products += power.n_products;
      const double lambda_max = power.lambda_max;

      auto record = [&](const qp::SolverStatistics &s)
      {
        result.qp_statistics.push_back(s);
        result.iterations += s.iterations;
        result.hessian_products += s.n_hessian_products;
        return s.converged();
      };
      auto qp_failure = [&](const std::string &where)
      {
        const qp::SolverStatistics &s = result.qp_statistics.back();
        std::ostringstream          message;
        message << "QP solver " << s.solver << " did not converge" << where
                << ": " << qp::to_string(s.reason) << " after " << s.iterations
                << " iterations, criterion " << s.final_criterion
                << " (tolerance " << s.tolerance << ")";
        result.reason = message.str();
      };

      bool has_friction = false;
      for (const double mu : problem_.mu())
        has_friction = has_friction || mu > 0;

      if (model_ == Model::cone || !has_friction)
      {
        if (record(solve_qp(r, nullptr, lambda_max)))
        {
          result.converged = true;
          result.reason    = "converged";
        }
        else
          qp_failure("");
      }
      else
      {
        auto slip_bounds = [&](const dealii::Vector<double> &x)
        {
          std::vector<double> psi(problem_.n_contacts());
          for (unsigned int i = 0; i < psi.size(); ++i)
            psi[i] = problem_.mu()[i] * std::max(x(dim * i), 0.);
          return psi;
        };
        // cold start: bonded first iterate (feasible for any load), as in
        // contact::ContactSolver; warm start: bounds from the given r
        std::vector<double> psi;
        bool                ok;
        if (r.linfty_norm() == 0 && first_ == FirstIterate::bonded)
          ok = record(solve_qp(r, nullptr, lambda_max));
        else if (r.linfty_norm() == 0)
        {
          psi.assign(problem_.n_contacts(), 0.);
          ok = record(solve_qp(r, &psi, lambda_max));
          psi.clear(); // the first change is not a number to compare
        }
        else
        {
          psi = slip_bounds(r);
          ok  = record(solve_qp(r, &psi, lambda_max));
        }
        if (!ok)
          qp_failure(" in the first Coulomb iterate");
        unsigned int growing = 0;
        for (unsigned int it = 0; ok; ++it)
        {
          const std::vector<double> old = psi;
          psi                           = slip_bounds(r);
          double relative               = 1.;
          if (!old.empty())
          {
            double change = 0, norm = 0;
            for (unsigned int i = 0; i < psi.size(); ++i)
            {
              change += std::pow(psi[i] - old[i], 2);
              norm += psi[i] * psi[i];
            }
            relative = norm > 0 ? std::sqrt(change / norm) : std::sqrt(change);
          }
          result.coulomb_changes.push_back(relative);
          if (!std::isfinite(relative))
          {
            result.reason = "Coulomb fixed point: non-finite slip bounds";
            break;
          }
          if (!old.empty() && relative <= coulomb_parameters_.tolerance)
          {
            result.converged = true;
            result.reason    = "converged";
            break;
          }
          const auto &changes = result.coulomb_changes;
          if (changes.size() > 1 && relative > changes[changes.size() - 2])
            ++growing;
          else
            growing = 0;
          if (growing >= coulomb_parameters_.divergence_window)
          {
            result.reason = "Coulomb fixed point diverged (the change of psi "
                            "grew in " +
                            std::to_string(growing) +
                            " consecutive iterations)";
            break;
          }
          if (it + 1 >= coulomb_parameters_.max_iterations)
          {
            result.reason = "Coulomb fixed point: maximum iterations (" +
                            std::to_string(coulomb_parameters_.max_iterations) +
                            ") reached, relative change " +
                            std::to_string(relative);
            break;
          }
          if (!record(solve_qp(r, &psi, lambda_max)))
          {
            qp_failure(" in Coulomb iteration " + std::to_string(it + 1));
            break;
          }
        }
      }
      result.fclib_error = fclib_error(problem_, r);
      result.wall_time   = timer.wall_time();
      return result;
    }
  } // namespace fclib
} // namespace dualcontact
