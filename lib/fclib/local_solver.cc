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
                             const FirstIterate                first,
                             const double                      proximal)
        : problem_(problem)
        , qp_parameters_(qp_parameters)
        , coulomb_parameters_(coulomb)
        , model_(model)
        , first_(first)
    {
      proximal_ = proximal;
      // round-off asymmetry (reduced global problems) is not worth a loop
      asymmetric_ = problem.asymmetry() > 1e-12;
      AssertThrow(proximal >= 0 && std::isfinite(proximal),
                  dealii::ExcMessage("proximal regularization must be >= 0"));
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

      // proximal term rho/2 ||r - center||^2 around the start r
      const double                        rho = proximal_ * lambda_max;
      qp::Problem<dealii::Vector<double>> qp;
      qp.hessian = [this, rho](dealii::Vector<double>       &dst,
                               const dealii::Vector<double> &src)
      {
        problem_.symmetric_vmult(dst, src);
        if (rho > 0)
          dst.add(rho, src);
      };
      qp.b = problem_.q();
      qp.b *= -1.;
      if (rho > 0)
        qp.b.add(rho, r);
      if (asymmetric_)
      {
        dealii::Vector<double> lagged;
        problem_.antisymmetric_vmult(lagged, r);
        qp.b -= lagged;
      }
      qp.constraints  = set;
      qp.lambda_max   = lambda_max + rho;
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
      const bool coulomb_loop =
        model_ == Model::coulomb_fixed_point && has_friction;

      auto slip_bounds = [&](const dealii::Vector<double> &x)
      {
        std::vector<double> psi(problem_.n_contacts());
        for (unsigned int i = 0; i < psi.size(); ++i)
          psi[i] = problem_.mu()[i] * std::max(x(dim * i), 0.);
        return psi;
      };
      // cold start: bonded or frictionless first iterate (bonded as in
      // contact::ContactSolver); warm start: bounds from the given r
      std::vector<double> psi;
      bool                bonded = false;
      if (r.linfty_norm() > 0)
        psi = slip_bounds(r);
      else if (first_ == FirstIterate::bonded)
        bonded = true;
      else
        psi.assign(problem_.n_contacts(), 0.);
      bool first_change = r.linfty_norm() == 0;

      unsigned int           growing = 0;
      dealii::Vector<double> previous;
      std::vector<double>   &measure =
        coulomb_loop ? result.coulomb_changes : result.proximal_steps;
      for (unsigned int it = 0;; ++it)
      {
        previous = r;
        if (!record(solve_qp(r, bonded ? nullptr : &psi, lambda_max)))
        {
          qp_failure(it == 0 ?
                       (coulomb_loop ? " in the first Coulomb iterate" : "") :
                       " in iteration " + std::to_string(it + 1));
          break;
        }
        const bool stepping = proximal_ > 0 || asymmetric_;
        if (!coulomb_loop && !stepping)
        {
          result.converged = true;
          result.reason    = "converged";
          break;
        }
        if (stepping)
        {
          previous -= r;
          const double norm = r.l2_norm();
          result.proximal_steps.push_back(norm > 0 ? previous.l2_norm() / norm :
                                                     previous.l2_norm());
        }
        if (coulomb_loop)
        {
          const std::vector<double> old = psi;
          psi                           = slip_bounds(r);
          double relative               = 1.;
          if (!first_change && !bonded)
          {
            double change = 0, norm = 0;
            for (unsigned int i = 0; i < psi.size(); ++i)
            {
              change += std::pow(psi[i] - old[i], 2);
              norm += psi[i] * psi[i];
            }
            relative = norm > 0 ? std::sqrt(change / norm) : std::sqrt(change);
          }
          bonded       = false;
          first_change = false;
          result.coulomb_changes.push_back(relative);
        }
        const double change = coulomb_loop ? result.coulomb_changes.back() : 0.;
        const double step   = stepping ? result.proximal_steps.back() : 0.;
        if (!std::isfinite(change) || !std::isfinite(step))
        {
          result.reason = "Coulomb/proximal loop: non-finite iterate";
          break;
        }
        if (change <= coulomb_parameters_.tolerance &&
            step <= coulomb_parameters_.tolerance)
        {
          result.converged = true;
          result.reason    = "converged";
          break;
        }
        // (damped by a proximal term, the changes need not decrease
        // monotonically: no divergence test then)
        if (coulomb_loop && proximal_ == 0 && measure.size() > 1 &&
            measure.back() > measure[measure.size() - 2])
          ++growing;
        else
          growing = 0;
        if (growing >= coulomb_parameters_.divergence_window)
        {
          result.reason =
            std::string(coulomb_loop ? "Coulomb fixed point" :
                                       "proximal / lagged-asymmetry loop") +
            " diverged (the change grew in " + std::to_string(growing) +
            " consecutive iterations)";
          break;
        }
        if (it + 1 >= coulomb_parameters_.max_iterations)
        {
          std::ostringstream message;
          message << (coulomb_loop ? "Coulomb fixed point" :
                                     "proximal / lagged-asymmetry loop")
                  << ": maximum iterations ("
                  << coulomb_parameters_.max_iterations
                  << ") reached, relative change of psi " << change
                  << ", relative step " << step;
          result.reason = message.str();
          break;
        }
      }
      result.fclib_error = fclib_error(problem_, r);
      result.wall_time   = timer.wall_time();
      return result;
    }
  } // namespace fclib
} // namespace dualcontact
