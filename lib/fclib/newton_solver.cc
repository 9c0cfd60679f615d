#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <fclib/accuracy.h>
#include <fclib/newton_solver.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include <deal.II/lac/lapack_templates.h>

#include <umfpack.h>

namespace dualcontact
{
  namespace fclib
  {
    void
    NewtonSolver::Parameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Newton");
      prm.declare_entry("Maximum steps",
                        "500",
                        dealii::Patterns::Integer(1),
                        "Model newton: Newton steps (LU factorizations of the "
                        "Jacobian) in all, over every proximal problem.");
      prm.declare_entry("Maximum steps per problem",
                        "20",
                        dealii::Patterns::Integer(1),
                        "Model newton: Newton steps on one proximal problem; "
                        "beyond them sigma grows and the problem is solved "
                        "again from its center.");
      prm.declare_entry("Sigma",
                        "1e-2",
                        dealii::Patterns::Double(0.),
                        "Model newton: first weight sigma of the proximal "
                        "term sigma/2 ||r - r^k||^2, relative to the mean "
                        "normal diagonal entry of W [-]; used when W is "
                        "singular or the plain Newton method fails.");
      prm.declare_entry("Sigma reduction",
                        "0.01",
                        dealii::Patterns::Double(0.),
                        "Model newton: factor of sigma after a proximal "
                        "problem solved (in (0, 1]) [-].");
      prm.declare_entry("Minimum sigma",
                        "1e-10",
                        dealii::Patterns::Double(0.),
                        "Model newton: the smallest sigma, relative as "
                        "Sigma [-].");
      prm.declare_entry("Armijo constant",
                        "1e-4",
                        dealii::Patterns::Double(0.),
                        "Model newton: sufficient decrease of 1/2 ||Phi||^2 "
                        "that the damped step must give, relative to the "
                        "linear model's (in (0, 1/2)) [-].");
      prm.declare_entry("Maximum step halvings",
                        "30",
                        dealii::Patterns::Integer(1),
                        "Model newton: halvings of the Newton step before "
                        "the line search gives up.");
      prm.declare_entry("Line search memory",
                        "10",
                        dealii::Patterns::Integer(1),
                        "Model newton: merits of the last steps that the "
                        "non-monotone line search compares with (1: "
                        "monotone Armijo).");
      prm.declare_entry("Extrapolation",
                        "true",
                        dealii::Patterns::Bool(),
                        "Model newton: extrapolate the proximal centers "
                        "(Nesterov's momentum, restarted when a step turns "
                        "back): the proximal point creeps along the flat "
                        "directions of a singular W by sigma-sized steps.");
      prm.declare_entry("Rho factor",
                        "1",
                        dealii::Patterns::Double(0.),
                        "Model newton: rho_i = factor / W_nn,i, the weight "
                        "of the velocity in z = r - rho u [-].");
      prm.leave_subsection();
    }


    void
    NewtonSolver::Parameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Newton");
      max_steps       = prm.get_integer("Maximum steps");
      max_inner_steps = prm.get_integer("Maximum steps per problem");
      sigma           = prm.get_double("Sigma");
      sigma_reduction = prm.get_double("Sigma reduction");
      sigma_min       = prm.get_double("Minimum sigma");
      armijo          = prm.get_double("Armijo constant");
      max_halvings    = prm.get_integer("Maximum step halvings");
      memory          = prm.get_integer("Line search memory");
      rho_factor      = prm.get_double("Rho factor");
      extrapolation   = prm.get_bool("Extrapolation");
      prm.leave_subsection();
    }


    void
    NewtonSolver::Parameters::check() const
    {
      AssertThrow(tolerance > 0,
                  dealii::ExcMessage("The tolerance of model newton must be "
                                     "positive."));
      AssertThrow(sigma > 0,
                  dealii::ExcMessage("Newton/Sigma must be positive."));
      AssertThrow(sigma_reduction > 0 && sigma_reduction <= 1,
                  dealii::ExcMessage("Newton/Sigma reduction must lie in "
                                     "(0, 1]."));
      AssertThrow(sigma_min > 0 && sigma_min <= sigma,
                  dealii::ExcMessage("Newton/Minimum sigma must be positive "
                                     "and at most Newton/Sigma."));
      AssertThrow(armijo > 0 && armijo < 0.5,
                  dealii::ExcMessage("Newton/Armijo constant must lie in "
                                     "(0, 1/2)."));
      AssertThrow(rho_factor > 0 && std::isfinite(rho_factor),
                  dealii::ExcMessage("Newton/Rho factor must be positive "
                                     "(rho = 0 takes the velocity out of "
                                     "the equations)."));
      AssertThrow(std::isfinite(sigma),
                  dealii::ExcMessage("Newton/Sigma must be finite."));
    }


    NewtonSolver::NewtonSolver(const LocalProblem &problem,
                               const Parameters   &parameters)
        : problem_(problem)
        , parameters_(parameters)
        , dim_(problem.spacedim())
    {
      parameters_.check();
      const auto        &W  = problem_.W();
      const unsigned int nc = problem_.n_contacts();
      // rho_i = 1 / W_nn,i: z = r - rho u then compares forces with forces
      double       sum      = 0;
      unsigned int positive = 0;
      for (unsigned int i = 0; i < nc; ++i)
      {
        const double w = W.el(dim_ * i, dim_ * i);
        if (w > 0)
        {
          sum += w;
          ++positive;
        }
      }
      mean_normal_diagonal_ = positive > 0 ? sum / positive : 1.;
      // one rho per contact (the tangential diagonal entries in the
      // tangential rows instead, 1 / W_tt: Capsules, Spheres-i099 and
      // spheres-in-a-box no longer converged in 500 steps)
      rho_.resize(nc);
      for (unsigned int i = 0; i < nc; ++i)
      {
        const double w = W.el(dim_ * i, dim_ * i);
        // a contact that W does not move (zero row): any positive scale
        rho_[i] = parameters_.rho_factor / (w > 0 ? w : mean_normal_diagonal_);
      }
      build_pattern();
      // a dense LAPACK LU where J is dense (W of an elastic scene: every
      // contact sees every other) or small (UMFPACK's fixed cost per call
      // is tens of microseconds: LMGC_GlobalFrictionContactProblem00046,
      // 27 unknowns, 29 -> 2 us a solve)
      const double density = static_cast<double>(columns_.size()) /
                             (static_cast<double>(problem_.size()) *
                              std::max<unsigned int>(problem_.size(), 1));
      dense_ = problem_.size() <= 64 || density >= 0.25;
    }


    NewtonSolver::~NewtonSolver()
    {
      if (symbolic_)
        umfpack_di_free_symbolic(&symbolic_);
    }


    void
    NewtonSolver::build_pattern()
    {
      const auto        &W  = problem_.W();
      const unsigned int n  = problem_.size();
      const unsigned int nc = problem_.n_contacts();
      row_start_.assign(n + 1, 0);
      columns_.clear();
      w_rows_.assign(n, {});
      block_position_.assign(n, 0);
      // J's rows of contact i are combinations of W's rows of contact i:
      // they share one column set, the union of those rows' and the
      // contact's own columns (marked in `position', -1 where unmarked:
      // linear in W's entries, which matters for a dense W)
      std::vector<int>          position(n, -1);
      std::vector<unsigned int> cols;
      for (unsigned int i = 0; i < nc; ++i)
      {
        const unsigned int first = dim_ * i;
        cols.clear();
        auto mark = [&](const unsigned int c)
        {
          if (position[c] < 0)
          {
            position[c] = 0;
            cols.push_back(c);
          }
        };
        for (unsigned int a = 0; a < dim_; ++a)
        {
          mark(first + a);
          for (auto e = W.begin(first + a); e != W.end(first + a); ++e)
            if (e->value() != 0)
              mark(e->column());
        }
        std::sort(cols.begin(), cols.end());
        for (unsigned int p = 0; p < cols.size(); ++p)
          position[cols[p]] = p;
        for (unsigned int a = 0; a < dim_; ++a)
        {
          const unsigned int row = first + a;
          row_start_[row]        = columns_.size();
          block_position_[row]   = position[first];
          columns_.insert(columns_.end(), cols.begin(), cols.end());
          for (auto e = W.begin(row); e != W.end(row); ++e)
            if (e->value() != 0)
              w_rows_[row].emplace_back(position[e->column()], e->value());
        }
        for (const unsigned int c : cols)
          position[c] = -1;
      }
      row_start_[n] = columns_.size();
      values_.resize(columns_.size());
    }


    void
    NewtonSolver::velocity(dealii::Vector<double>       &u,
                           const dealii::Vector<double> &r,
                           const dealii::Vector<double> &center,
                           const double                  sigma,
                           Result                       &result) const
    {
      problem_.velocity(u, r);
      ++result.products;
      if (sigma > 0)
        for (unsigned int k = 0; k < u.size(); ++k)
          u(k) += sigma * (r(k) - center(k));
    }


    void
    NewtonSolver::residual(dealii::Vector<double>       &phi,
                           const dealii::Vector<double> &r,
                           const dealii::Vector<double> &u,
                           std::vector<double>          *D) const
    {
      const unsigned int nc = problem_.n_contacts();
      const unsigned int d  = dim_;
      if (D)
        D->assign(nc * d * d, 0.);
      double z[3];
      for (unsigned int i = 0; i < nc; ++i)
      {
        const unsigned int first = d * i;
        const double       mu    = problem_.mu()[i];
        for (unsigned int a = 0; a < d; ++a)
          z[a] = r(first + a) - rho_[i] * u(first + a);
        const double pn     = std::max(z[0], 0.);
        const double radius = mu * pn;
        double       t      = 0;
        for (unsigned int a = 1; a < d; ++a)
          t += z[a] * z[a];
        t = std::sqrt(t);
        // P(z): the normal part on R+, the tangential one on the disc
        phi(first)        = r(first) - pn;
        const bool slides = t > radius;
        for (unsigned int a = 1; a < d; ++a)
          phi(first + a) =
            r(first + a) - (slides ? (t > 0 ? radius * z[a] / t : 0.) : z[a]);
        if (!D)
          continue;
        double *block = D->data() + i * d * d;
        block[0]      = z[0] > 0 ? 1. : 0.;
        if (!slides)
        {
          // sticking (or z_t = 0 on an open contact: measure zero)
          for (unsigned int a = 1; a < d; ++a)
            block[a * d + a] = 1.;
        }
        else
        {
          // radius z_t / |z_t|: tangent part radius / t (I - n n'), and
          // mu n through the radius where z_n > 0
          for (unsigned int a = 1; a < d; ++a)
          {
            const double na = z[a] / t;
            for (unsigned int b = 1; b < d; ++b)
              block[a * d + b] =
                radius / t * ((a == b ? 1. : 0.) - na * z[b] / t);
            block[a * d] = z[0] > 0 ? mu * na : 0.;
          }
        }
      }
    }


    bool
    NewtonSolver::solve_newton_system(const std::vector<double>    &D,
                                      const double                  sigma,
                                      const dealii::Vector<double> &phi,
                                      dealii::Vector<double>       &x) const
    {
      const unsigned int d  = dim_;
      const unsigned int nc = problem_.n_contacts();
      // J_i = (I - D_i) E_i + rho_i D_i (W + sigma I)_i, E_i the rows of
      // the identity of contact i
      std::fill(values_.begin(), values_.end(), 0.);
      for (unsigned int i = 0; i < nc; ++i)
      {
        const double *block = D.data() + i * d * d;
        for (unsigned int a = 0; a < d; ++a)
        {
          const unsigned int row   = d * i + a;
          double            *J_row = values_.data() + row_start_[row];
          const unsigned int diag  = block_position_[row];
          for (unsigned int b = 0; b < d; ++b)
          {
            const double Dab = block[a * d + b];
            J_row[diag + b] += (a == b ? 1. : 0.) - Dab;
            if (Dab == 0)
              continue;
            const double scale = rho_[i] * Dab;
            for (const auto &[p, w] : w_rows_[d * i + b])
              J_row[p] += scale * w;
            J_row[diag + b] += scale * sigma;
          }
        }
      }
      return dense_ ? solve_dense(phi, x) : solve_sparse(phi, x);
    }


    bool
    NewtonSolver::solve_dense(const dealii::Vector<double> &phi,
                              dealii::Vector<double>       &x) const
    {
      const unsigned int n = problem_.size();
      // J column-major from its rows
      dense_J_.assign(static_cast<std::size_t>(n) * n, 0.);
      for (unsigned int row = 0; row < n; ++row)
        for (int k = row_start_[row]; k < row_start_[row + 1]; ++k)
          dense_J_[static_cast<std::size_t>(columns_[k]) * n + row] =
            values_[k];
      pivots_.resize(n);
      const dealii::types::blas_int size = n, one = 1;
      dealii::types::blas_int       info = 0;
      dealii::getrf(
        &size, &size, dense_J_.data(), &size, pivots_.data(), &info);
      if (info != 0)
        return false;
      x = phi;
      x *= -1.;
      const char no_transpose = 'N';
      dealii::getrs(&no_transpose,
                    &size,
                    &one,
                    dense_J_.data(),
                    &size,
                    pivots_.data(),
                    x.data(),
                    &size,
                    &info);
      return info == 0 && std::isfinite(x.l2_norm());
    }


    bool
    NewtonSolver::solve_sparse(const dealii::Vector<double> &phi,
                               dealii::Vector<double>       &x) const
    {
      const unsigned int n = problem_.size();
      // UMFPACK reads compressed columns: J's rows are the columns of J',
      // so the system J x = b is A' x = b for A = J'.  J's pattern is
      // fixed: its analysis (the fill-reducing ordering) is done once
      void  *numeric = nullptr;
      double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
      umfpack_di_defaults(control);
      // no iterative refinement: a Newton step needs no more accuracy
      // than the factorization gives, and each refinement step costs a
      // product with J
      control[UMFPACK_IRSTEP] = 0;
      if (!symbolic_)
      {
        const int n_int  = static_cast<int>(n);
        const int status = umfpack_di_symbolic(n_int,
                                               n_int,
                                               row_start_.data(),
                                               columns_.data(),
                                               values_.data(),
                                               &symbolic_,
                                               control,
                                               info);
        AssertThrow(status == UMFPACK_OK,
                    dealii::ExcMessage("UMFPACK's analysis of the Newton "
                                       "Jacobian failed with status " +
                                       std::to_string(status)));
      }
      int  status = umfpack_di_numeric(row_start_.data(),
                                      columns_.data(),
                                      values_.data(),
                                      symbolic_,
                                      &numeric,
                                      control,
                                      info);
      bool solved = false;
      if (status == UMFPACK_OK)
      {
        dealii::Vector<double> rhs(phi);
        rhs *= -1.;
        status = umfpack_di_solve(UMFPACK_At,
                                  row_start_.data(),
                                  columns_.data(),
                                  values_.data(),
                                  x.data(),
                                  rhs.data(),
                                  numeric,
                                  control,
                                  info);
        solved = status == UMFPACK_OK && std::isfinite(x.l2_norm());
      }
      if (numeric)
        umfpack_di_free_numeric(&numeric);
      return solved;
    }


    NewtonSolver::Outcome
    NewtonSolver::newton(dealii::Vector<double>       &r,
                         const dealii::Vector<double> &center,
                         const double                  sigma,
                         const double                  tolerance,
                         Result                       &result) const
    {
      const unsigned int     n = problem_.size();
      dealii::Vector<double> u(n), phi(n), step(n), trial(n), trial_u(n),
        trial_phi(n);
      std::vector<double> D;
      velocity(u, r, center, sigma, result);
      residual(phi, r, u, &D);
      double merit = 0.5 * phi.norm_sqr();
      // non-monotone Armijo (Grippo, Lampariello and Lucidi): the trial is
      // compared with the largest merit of the last few steps, which lets
      // the semismooth steps cross the kinks of Phi that a monotone rule
      // cuts into many halvings
      std::vector<double> recent{merit};
      for (unsigned int k = 0; k < parameters_.max_inner_steps; ++k)
      {
        if (fclib_error(problem_, r, u) <= tolerance)
          return Outcome::converged;
        if (result.steps >= parameters_.max_steps)
          return Outcome::step_limit;
        ++result.steps;
        if (!solve_newton_system(D, sigma, phi, step))
          return Outcome::singular;
        // Armijo on 1/2 ||Phi||^2, whose slope along the Newton step is
        // -||Phi||^2
        double t        = 1;
        bool   accepted = false;
        for (unsigned int h = 0; h <= parameters_.max_halvings; ++h, t *= 0.5)
        {
          trial = r;
          trial.add(t, step);
          velocity(trial_u, trial, center, sigma, result);
          residual(trial_phi, trial, trial_u, nullptr);
          const double trial_merit = 0.5 * trial_phi.norm_sqr();
          const double reference =
            *std::max_element(recent.begin(), recent.end());
          if (trial_merit <= reference - 2. * parameters_.armijo * t * merit)
          {
            accepted = true;
            break;
          }
          ++result.halvings;
        }
        if (!accepted)
          return Outcome::line_search_failed;
        r = trial;
        u = trial_u;
        residual(phi, r, u, &D);
        merit = 0.5 * phi.norm_sqr();
        recent.push_back(merit);
        if (recent.size() > parameters_.memory)
          recent.erase(recent.begin());
      }
      return fclib_error(problem_, r, u) <= tolerance ? Outcome::converged :
                                                        Outcome::step_limit;
    }


    NewtonSolver::Result
    NewtonSolver::solve(dealii::Vector<double> &r) const
    {
      AssertThrow(r.size() == problem_.size(),
                  dealii::ExcMessage("The start of the Newton solver has " +
                                     std::to_string(r.size()) +
                                     " entries, the problem " +
                                     std::to_string(problem_.size()) + "."));
      dealii::Timer timer;
      Result        result;
      const double  tol = parameters_.tolerance;
      // the inner solves a tenth below the goal: the proximal term's
      // perturbation sigma (r^{k+1} - r^k) takes the rest
      const double inner_tol = 0.1 * tol;

      // the plain method first: a regular W needs no proximal term
      dealii::Vector<double> center(r);
      const Outcome          plain = parameters_.plain_first ?
                                       newton(r, center, 0., tol, result) :
                                       Outcome::step_limit;
      result.plain_steps           = result.steps;
      result.errors.push_back(fclib_error(problem_, r));
      if (plain == Outcome::converged)
      {
        result.converged   = true;
        result.reason      = "converged (plain Newton method)";
        result.fclib_error = result.errors.back();
        result.wall_time   = timer.wall_time();
        return result;
      }
      if (!std::isfinite(r.l2_norm()))
        r = center;

      double sigma = parameters_.sigma;
      // a sigma at which a Newton solve failed is not tried again: sigma
      // stays above it (else the loop alternates between a sigma that
      // works and one that wastes a whole solve's steps)
      double                 sigma_floor = parameters_.sigma_min;
      double                 last_error  = result.errors.back();
      dealii::Vector<double> previous(r), start(r);
      unsigned int           momentum = 0;
      while (true)
      {
        // Nesterov's extrapolation of the center (Gueler's accelerated
        // proximal point), restarted when the step turns back
        center = r;
        if (parameters_.extrapolation && momentum > 0)
        {
          const double beta = (momentum - 1.) / (momentum + 2.);
          center.add(beta, r);
          center.add(-beta, previous);
        }
        start          = r;
        const double s = sigma * mean_normal_diagonal_;
        // the proximal problems need not be solved far below the error of
        // their center: the next one moves it anyway
        const double  tolerance = std::max(inner_tol, 1e-2 * last_error);
        const Outcome inner     = newton(r, center, s, tolerance, result);
        ++result.proximal_iterations;
        result.sigmas.push_back(sigma);
        if (inner == Outcome::converged)
        {
          const double error = fclib_error(problem_, r);
          result.errors.push_back(error);
          if (error <= tol)
          {
            result.converged = true;
            result.reason    = "converged (proximal Newton method)";
            break;
          }
          last_error = error;
          sigma = std::max(sigma_floor, sigma * parameters_.sigma_reduction);
          {
            // restart when the new step points against the last one
            dealii::Vector<double> step(r), last(start);
            step -= start;
            last -= previous;
            momentum = (step * last < 0) ? 1 : momentum + 1;
          }
          previous = start;
        }
        else
        {
          // back to the center with a stronger proximal term
          r           = start;
          momentum    = 0;
          sigma_floor = std::max(sigma_floor, 10 * sigma);
          sigma *= 10;
        }
        if (result.steps >= parameters_.max_steps)
        {
          result.reason =
            "not converged: " + std::to_string(parameters_.max_steps) +
            " Newton steps (Newton/Maximum steps)";
          break;
        }
      }
      result.fclib_error = fclib_error(problem_, r);
      result.wall_time   = timer.wall_time();
      return result;
    }
  } // namespace fclib
} // namespace dualcontact
