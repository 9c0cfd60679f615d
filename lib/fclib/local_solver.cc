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
    void
    LocalSolver::Parameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Model",
                        "coulomb",
                        dealii::Patterns::Selection(model_names.choices()),
                        "coulomb: the fixed point over Tresca QPs (bound x "
                        "disc blocks), which solves the Coulomb problem; "
                        "cone: one QP over the Coulomb cones, a convex "
                        "relaxation (no De Saxce shift), 3D only; desaxce: "
                        "the cone QPs with De Saxce's shift mu ||u_t|| of the "
                        "previous iterate added to q_n, a fixed point that "
                        "solves the Coulomb problem, 3D only.");
      prm.declare_entry("First Coulomb iterate",
                        "bonded",
                        dealii::Patterns::Selection(
                          first_iterate_names.choices()),
                        "Model coulomb, cold start: bonded (no bound on the "
                        "tangential forces, as the contact solver of the "
                        "scenes) or frictionless (slip bounds 0); bonded "
                        "can be unbounded below when W is singular "
                        "(rigid-body problems).");
      prm.declare_entry("Inexact QPs",
                        "true",
                        dealii::Patterns::Bool(),
                        "Adapt the QP tolerance to the progress of the loop "
                        "(loose first, the QP tolerance at the end): "
                        "eps_{k+1} = max(eps, min(eps_k, factor * change_k)).");
      prm.declare_entry("Initial QP tolerance",
                        "1e-2",
                        dealii::Patterns::Double(0.),
                        "Inexact QPs: relative tolerance of the first QP [-] "
                        "(never below the QP solver's tolerance).");
      prm.declare_entry("QP tolerance factor",
                        "0.1",
                        dealii::Patterns::Double(0.),
                        "Inexact QPs: factor of the last change of the loop "
                        "in the next QP tolerance [-].");
      prm.declare_entry(
        "Proximal regularization",
        "auto",
        dealii::Patterns::Anything(),
        "off | on | auto | RHO.  Proximal point: every QP gets rho/2 ||r - "
        "r_previous||^2, strictly convex for singular W (rigid-body "
        "problems); the loop then stops on the perturbation of q it leaves, "
        "||rho (r - r_previous)|| <= (Coulomb tolerance) ||q||.  auto: the "
        "plain loop first, and the proximal loop from its last good iterate "
        "if it fails (singular W); a number: on, with that initial rho "
        "(relative to lambda_max(W)); 0 = off.");
      prm.declare_entry("Initial rho",
                        "0.1",
                        dealii::Patterns::Double(0.),
                        "Proximal point: initial rho relative to "
                        "lambda_max(W) [-].");
      prm.declare_entry("Adaptive rho",
                        "true",
                        dealii::Patterns::Bool(),
                        "Proximal point: divide rho by the rho factor after a "
                        "cheap QP, multiply it (and redo the QP) after a QP "
                        "that did not converge.");
      prm.declare_entry("Rho range",
                        "1e-6, 10",
                        dealii::Patterns::List(dealii::Patterns::Double(0.),
                                               2,
                                               2),
                        "Proximal point: smallest and largest rho relative to "
                        "lambda_max(W) [-].");
      prm.declare_entry("Rho factor",
                        "2",
                        dealii::Patterns::Double(1.),
                        "Proximal point: factor of the changes of rho [-].");
      prm.declare_entry("Rho decrease below",
                        "50",
                        dealii::Patterns::Integer(0),
                        "Proximal point: rho decreases after a QP of at most "
                        "this many iterations.");
      prm.declare_entry("Rho increase above",
                        "150",
                        dealii::Patterns::Integer(0),
                        "Proximal point: rho increases after a QP of more "
                        "than this many iterations.");
      prm.declare_entry("Proximal extrapolation",
                        "true",
                        dealii::Patterns::Bool(),
                        "Proximal point: center the next QP at the "
                        "extrapolated iterate r + beta (r - r_previous) "
                        "(Nesterov's beta, restarted when the step turns "
                        "back): accelerates the proximal loop along the small "
                        "curvatures of a singular W.");
      prm.declare_entry("Contact scaling",
                        "true",
                        dealii::Patterns::Bool(),
                        "Solve the QPs in the unknowns r_i / s_i with s_i = "
                        "W_nn,i^-1/2 per contact (the same for its normal and "
                        "tangential unknowns, so discs and cones keep their "
                        "shape): the diagonal of the Hessian becomes 1 on the "
                        "normals, which evens out contacts of different "
                        "compliance (e.g. nodes of different tributary area).");
      prm.declare_entry("Lanczos tolerance",
                        "1e-2",
                        dealii::Patterns::Double(0., 1.),
                        "The Lanczos estimate of lambda_max of the QPs' "
                        "Hessian stops when it changes by less than this "
                        "(relative) from one step to the next; the QP "
                        "solver's `Power iteration safety factor' multiplies "
                        "it. Unit: none.");
      prm.declare_entry("Plain QP iterations in auto",
                        "500",
                        dealii::Patterns::Integer(1),
                        "Proximal regularization = auto: iteration limit of "
                        "the plain loop's QPs (a QP that needs more counts "
                        "as failed and the proximal loop takes over).");
      prm.declare_entry("Bonded QP iterations in auto",
                        "200",
                        dealii::Patterns::Integer(1),
                        "Proximal regularization = auto: iteration limit of "
                        "the plain loop's bonded QP (the first Coulomb "
                        "iterate, no slip bound), which is unbounded below "
                        "when W is singular along a tangential direction "
                        "that q pulls along (rigid bodies): a QP that needs "
                        "more counts as failed.");
      prm.declare_entry("Newton after a failed plain loop",
                        "true",
                        dealii::Patterns::Bool(),
                        "Proximal regularization = auto: when the plain loop "
                        "fails, the semismooth Newton method of model newton "
                        "(subsection Newton) to an FCLIB error at most the "
                        "Coulomb tolerance, from the cold start; the "
                        "proximal QP loop runs only if it fails too.  false: "
                        "the proximal QP loop at once.");
      prm.declare_entry("Polish",
                        "true",
                        dealii::Patterns::Bool(),
                        "Model coulomb: when the loop has converged on its "
                        "relative criteria but the FCLIB error of its "
                        "solution is above the Coulomb tolerance, refine "
                        "it: where W is stored dense, the plain loop once "
                        "more from it with QPs ten times tighter; else "
                        "proximal Newton steps (model newton) down to the "
                        "tolerance.  The result is kept if its error is "
                        "smaller.");
      prm.declare_entry("Proximal maximum iterations",
                        "5000",
                        dealii::Patterns::Integer(1),
                        "Limit of the proximal loop's iterations (the larger "
                        "of this and Coulomb/Maximum iterations).");
      NewtonSolver::Parameters::declare_parameters(prm);
    }


    void
    LocalSolver::Parameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      model   = model_names.value(prm.get("Model"));
      first   = first_iterate_names.value(prm.get("First Coulomb iterate"));
      inexact = prm.get_bool("Inexact QPs");
      initial_qp_tolerance = prm.get_double("Initial QP tolerance");
      qp_tolerance_factor  = prm.get_double("QP tolerance factor");
      rho                  = prm.get_double("Initial rho");
      // (a number there sets rho)
      parse_proximal(prm.get("Proximal regularization"));
      adaptive_rho            = prm.get_bool("Adaptive rho");
      const std::string range = prm.get("Rho range");
      rho_min                 = std::stod(range.substr(0, range.find(',')));
      rho_max                 = std::stod(range.substr(range.find(',') + 1));
      rho_factor              = prm.get_double("Rho factor");
      rho_decrease_below      = prm.get_integer("Rho decrease below");
      rho_increase_above      = prm.get_integer("Rho increase above");
      extrapolation           = prm.get_bool("Proximal extrapolation");
      contact_scaling         = prm.get_bool("Contact scaling");
      lanczos_tolerance       = prm.get_double("Lanczos tolerance");
      proximal_max_iterations = prm.get_integer("Proximal maximum iterations");
      auto_plain_qp_max_iterations =
        prm.get_integer("Plain QP iterations in auto");
      auto_bonded_qp_max_iterations =
        prm.get_integer("Bonded QP iterations in auto");
      newton_after_plain_loop =
        prm.get_bool("Newton after a failed plain loop");
      polish = prm.get_bool("Polish");
      newton.parse_parameters(prm);
      check();
    }


    void
    LocalSolver::Parameters::parse_proximal(const std::string &value)
    {
      if (value == "off")
        proximal = Proximal::off;
      else if (value == "on")
        proximal = Proximal::on;
      else if (value == "auto")
        proximal = Proximal::automatic;
      else
      {
        double      x    = -1;
        std::size_t used = 0;
        try
        {
          x = std::stod(value, &used);
        }
        catch (const std::exception &)
        {
          used = 0;
        }
        AssertThrow(used == value.size() && x >= 0 && std::isfinite(x),
                    dealii::ExcMessage("Proximal regularization: `" + value +
                                       "' is none of off, on, auto or a "
                                       "number >= 0"));
        proximal = x > 0 ? Proximal::on : Proximal::off;
        if (x > 0)
          rho = x;
      }
    }


    void
    LocalSolver::Parameters::check() const
    {
      newton.check();
      AssertThrow(initial_qp_tolerance > 0 &&
                    std::isfinite(initial_qp_tolerance),
                  dealii::ExcMessage("Initial QP tolerance must be > 0"));
      AssertThrow(qp_tolerance_factor > 0 && std::isfinite(qp_tolerance_factor),
                  dealii::ExcMessage("QP tolerance factor must be > 0"));
      AssertThrow(rho > 0 && std::isfinite(rho),
                  dealii::ExcMessage("Initial rho must be > 0"));
      AssertThrow(rho_min > 0 && rho_min <= rho_max && std::isfinite(rho_max),
                  dealii::ExcMessage("Rho range: need 0 < rho_min <= rho_max"));
      AssertThrow(rho_factor >= 1 && std::isfinite(rho_factor),
                  dealii::ExcMessage("Rho factor must be >= 1"));
      AssertThrow(rho_increase_above >= rho_decrease_below,
                  dealii::ExcMessage("Rho increase above must be >= Rho "
                                     "decrease below"));
      AssertThrow(lanczos_tolerance > 0 && lanczos_tolerance < 1,
                  dealii::ExcMessage("Lanczos tolerance must be in (0, 1)"));
      AssertThrow(proximal_max_iterations >= 1,
                  dealii::ExcMessage("Proximal maximum iterations must be "
                                     ">= 1"));
    }


    namespace
    {
      LocalSolver::Parameters
      first_version(const Model        model,
                    const FirstIterate first,
                    const double       proximal)
      {
        AssertThrow(proximal >= 0 && std::isfinite(proximal),
                    dealii::ExcMessage("proximal regularization must be >= 0"));
        LocalSolver::Parameters p;
        p.model           = model;
        p.first           = first;
        p.inexact         = false;
        p.proximal        = proximal > 0 ? Proximal::on : Proximal::off;
        p.adaptive_rho    = false;
        p.extrapolation   = false;
        p.contact_scaling = false;
        if (proximal > 0)
          p.rho = proximal;
        return p;
      }
    } // namespace


    LocalSolver::LocalSolver(const LocalProblem               &problem,
                             const qp::SolverParameters       &qp_parameters,
                             const contact::CoulombParameters &coulomb,
                             const Model                       model,
                             const FirstIterate                first,
                             const double                      proximal)
        : LocalSolver(problem,
                      qp_parameters,
                      coulomb,
                      first_version(model, first, proximal))
    {
    }


    LocalSolver::LocalSolver(const LocalProblem               &problem,
                             const qp::SolverParameters       &qp_parameters,
                             const contact::CoulombParameters &coulomb,
                             const Parameters                 &parameters)
        : problem_(problem)
        , qp_parameters_(qp_parameters)
        , coulomb_parameters_(coulomb)
        , parameters_(parameters)
    {
      parameters.check();
      // round-off asymmetry (reduced global problems) is not worth a loop
      asymmetric_ = problem.delassus().asymmetry() > 1e-12;
      // contact scaling s_i = W_nn,i^-1/2 (1 where W_nn,i = 0), the same
      // for the unknowns of a contact so that discs and cones keep their
      // shape
      if (parameters.contact_scaling && problem.size() > 0)
      {
        const unsigned int dim = problem.spacedim();
        scale_.reinit(problem.size());
        bool uniform = true;
        for (unsigned int i = 0; i < problem.n_contacts(); ++i)
        {
          const double w = problem.delassus().matrix().el(dim * i, dim * i);
          const double s = w > 0 ? 1. / std::sqrt(w) : 1.;
          for (unsigned int k = 0; k < dim; ++k)
            scale_(dim * i + k) = s;
          uniform = uniform && s == scale_(0);
        }
        if (uniform) // a global factor changes nothing
          scale_.reinit(0);
        else if (problem.size() <= 2000)
          // the copy and scalings it saves cost about 3/n of a product:
          // beyond a few thousand unknowns not worth a second dense matrix
          scaled_W_ = problem.delassus().scaled_dense_symmetric(scale_);
      }
      AssertThrow(parameters.model != Model::newton,
                  dealii::ExcMessage("model newton is solved by "
                                     "fclib::NewtonSolver, not by QPs"));
      AssertThrow((parameters.model != Model::cone &&
                   parameters.model != Model::desaxce_fixed_point) ||
                    problem.spacedim() == 3,
                  dealii::ExcMessage("the cone model needs a 3D problem (the "
                                     "cone block has 3 unknowns)"));
    }


    void
    LocalSolver::scaled_vmult(dealii::Vector<double>       &dst,
                              const dealii::Vector<double> &src) const
    {
      if (!scaled_W_.empty())
      {
        DelassusOperator::dense_vmult(scaled_W_, dst, src);
        return;
      }
      scale_work_ = src;
      scale_work_.scale(scale_);
      problem_.delassus().symmetric_vmult(dst, scale_work_);
      dst.scale(scale_);
    }


    double
    LocalSolver::estimate_lambda_max(
      const std::function<void(dealii::Vector<double> &,
                               const dealii::Vector<double> &)> &hessian,
      Result                                                    &result) const
    {
      const qp::PowerIterationResult power =
        qp::lanczos_lambda_max<dealii::Vector<double>>(
          hessian,
          problem_.q(),
          qp_parameters_.power_max_iterations,
          parameters_.lanczos_tolerance,
          qp_parameters_.power_safety_factor);
      result.hessian_products += power.n_products;
      result.power_products += power.n_products;
      return power.lambda_max;
    }


    qp::SolverStatistics
    LocalSolver::solve_qp(dealii::Vector<double>    &r,
                          const std::vector<double> *psi,
                          const double               rho,
                          const double               tolerance,
                          const unsigned int         max_iterations) const
    {
      const unsigned int dim = problem_.spacedim();
      // the contact scaling in the plain loop only: the proximal loop
      // (rigid-body problems) was measured without it, and with it mpgp
      // did not reach 1e-8 on spheres-in-a-box in 1000 proximal QPs
      const bool scaled = scale_.size() == r.size() && rho == 0;
      // The set's shape per contact (0: normal bound only, 1: tangential
      // boxes [0, 0], 2: disc or 2D box of the slip bound, 3: cone) and the
      // slip bounds; a QP of the same shape as the last one keeps its set
      // and changes the radii only
      std::vector<unsigned char> shape(problem_.n_contacts());
      std::vector<double>        radius(problem_.n_contacts(), 0.);
      for (unsigned int i = 0; i < problem_.n_contacts(); ++i)
      {
        const double mu = problem_.mu()[i];
        if (parameters_.model == Model::cone ||
            parameters_.model == Model::desaxce_fixed_point)
          shape[i] = 3;
        // psi == nullptr: bonded iterate, no bound on frictional contacts
        else if (mu > 0 && psi == nullptr)
          shape[i] = 0;
        else
        {
          // scaled unknowns r~ = r / s_i: the disc radius too
          const double s = scaled ? scale_(dim * i) : 1.;
          radius[i]      = mu > 0 ? (*psi)[i] / s : 0.;
          shape[i]       = radius[i] == 0. ? 1 : 2; // r_t = 0: boxes
        }
      }
      if (!set_ || shape != set_shape_)
      {
        set_ = std::make_shared<qp::SeparableSet<dealii::Vector<double>>>();
        for (unsigned int i = 0; i < problem_.n_contacts(); ++i)
        {
          const unsigned int first = dim * i;
          if (shape[i] == 3)
          {
            set_->add_cone(first, problem_.mu()[i]);
            continue;
          }
          set_->add_bound(first, 0.);
          if (shape[i] == 1) // boxes, which mprgp also takes
            for (unsigned int k = 1; k < dim; ++k)
              set_->add_box(first + k, 0., 0.);
          else if (shape[i] == 2 && dim == 3)
            set_->add_disc(first + 1, radius[i]);
          else if (shape[i] == 2)
            set_->add_box(first + 1, -radius[i], radius[i]);
        }
        set_->finalize(r);
        set_shape_ = shape;
      }
      else
      {
        // the blocks in the order they were added above
        unsigned int disc = 0, box = 0;
        for (unsigned int i = 0; i < problem_.n_contacts(); ++i)
          if (shape[i] == 1)
            box += dim - 1;
          else if (shape[i] == 2 && dim == 3)
            set_->set_disc_radius(disc++, radius[i]);
          else if (shape[i] == 2)
            set_->set_box_bounds(box++, -radius[i], radius[i]);
      }
      const std::shared_ptr<qp::SeparableSet<dealii::Vector<double>>> &set =
        set_;

      // proximal term rho/2 ||r - center||^2 around the start r; with the
      // contact scaling the same QP in r~ = S^-1 r: Hessian S W_s S, b~ =
      // S b, so that its solution is the unscaled one
      qp::Problem<dealii::Vector<double>> qp;
      if (scaled)
        qp.hessian =
          [this](dealii::Vector<double> &dst, const dealii::Vector<double> &src)
        { scaled_vmult(dst, src); };
      else
        qp.hessian = [this, rho](dealii::Vector<double>       &dst,
                                 const dealii::Vector<double> &src)
        {
          problem_.delassus().symmetric_vmult(dst, src);
          if (rho > 0)
            dst.add(rho, src);
        };
      qp.b = problem_.q();
      if (shift_.size() == qp.b.size())
        qp.b += shift_;
      qp.b *= -1.;
      if (rho > 0)
        qp.b.add(rho, r);
      if (asymmetric_)
      {
        dealii::Vector<double> lagged;
        problem_.delassus().antisymmetric_vmult(lagged, r);
        qp.b -= lagged;
      }
      if (scaled)
        qp.b.scale(scale_);
      qp.constraints = set;
      // W (dense Delassus operator): `auto' keeps the given parameters
      qp.hessian_storage = dualcontact::qp::HessianStorage::dense_matrix;
      qp.lambda_max      = scaled ? qp_lambda_max_ : lambda_max_ + rho;
      qp.semidefinite    = true;
      // the QP criterion is relative to ||b||; the proximal and lagged
      // terms make ||b|| larger than ||q||, and the error that matters is
      // the one in q: tolerance relative to ||q||
      qp::SolverParameters   prm = qp_parameters_;
      const double           b   = qp.b.l2_norm();
      dealii::Vector<double> scaled_q(problem_.q());
      if (scaled)
        scaled_q.scale(scale_);
      const double q     = scaled_q.l2_norm();
      prm.tolerance      = tolerance;
      prm.max_iterations = std::min(prm.max_iterations, max_iterations);
      if (b > q && q > 0)
        prm.tolerance *= q / b;
      // one solver for all QPs, its tolerance and limit set per QP:
      // creating one checks and parses the parameters, a tenth of the work
      // of a short QP on a small problem (Hertz L3)
      if (!solver_)
        solver_ = qp::create<dealii::Vector<double>>(prm);
      else
        solver_->set_tolerance(prm.tolerance, prm.max_iterations);
      qp::SolverBase<dealii::Vector<double>> *solver = solver_.get();

      // The plain QPs of a loop have the same Hessian and b; each starts
      // from the last one's solution, whose gradient the solver ended with
      // (Problem::start_gradient: one product fewer per QP, unless the new
      // set cuts the start)
      // (De Saxce's shift changes b from one QP to the next)
      const bool plain = rho == 0 && !asymmetric_ &&
                         parameters_.model != Model::desaxce_fixed_point;
      dealii::Vector<double> x(r);
      if (plain && end_gradient_ && end_scaled_ == scaled &&
          end_r_.size() == r.size() && end_r_ == r)
      {
        x                 = end_x_; // exactly, not r / s rounded
        qp.start_gradient = end_gradient_;
        // for the contacts the new bounds move: S W_s S d by columns
        qp.hessian_add_sparse =
          [this, scaled](dealii::Vector<double>         &dst,
                         const dealii::Vector<double>   &d,
                         const std::vector<std::size_t> &indices)
        {
          if (!scaled)
          {
            problem_.delassus().add_symmetric_columns(dst, d, indices);
            return;
          }
          if (!scaled_W_.empty())
          {
            DelassusOperator::dense_add_columns(scaled_W_, dst, d, indices);
            return;
          }
          dealii::Vector<double> sd(d.size()), column_sum(d.size());
          for (const std::size_t j : indices)
            sd(j) = scale_(j) * d(j);
          problem_.delassus().add_symmetric_columns(column_sum, sd, indices);
          for (unsigned int i = 0; i < dst.size(); ++i)
            dst(i) += scale_(i) * column_sum(i);
        };
      }
      else if (scaled)
        for (unsigned int k = 0; k < x.size(); ++k)
          x(k) /= scale_(k);
      const qp::SolverStatistics statistics = solver->solve(qp, x);
      r.equ(1., x);
      if (scaled)
        r.scale(scale_);
      const dealii::Vector<double> *gradient = solver->final_gradient();
      if (plain && gradient)
      {
        end_r_ = r;
        end_x_ = x;
        if (!end_gradient_ || end_gradient_.use_count() > 1)
          end_gradient_ = std::make_shared<dealii::Vector<double>>();
        *end_gradient_ = *gradient;
        end_scaled_    = scaled;
      }
      else
        end_gradient_.reset();
      return statistics;
    }


    LocalSolver::Result
    LocalSolver::solve(dealii::Vector<double> &r) const
    {
      AssertThrow(r.size() == problem_.size(),
                  dealii::ExcMessage("LocalSolver: start vector of size " +
                                     std::to_string(r.size()) + ", expected " +
                                     std::to_string(problem_.size())));
      dealii::Timer timer;
      Result        result;

      // lambda_max(W_s): once per problem, by Lanczos (the Hessians of all QPs
      // are W_s
      // + rho I, only the bounds change)
      if (qp_lambda_max_ == 0)
      {
        // (Lanczos: fewer products than the power iteration for the same
        // tolerance, which matters for the short loops of small problems);
        // with the contact scaling, of S W_s S
        qp_lambda_max_ = estimate_lambda_max(
          [this](dealii::Vector<double> &dst, const dealii::Vector<double> &src)
          {
            if (scale_.size() == src.size())
              scaled_vmult(dst, src);
            else
              problem_.delassus().symmetric_vmult(dst, src);
          },
          result);
        if (scale_.size() == 0)
          lambda_max_ = qp_lambda_max_;
      }

      // proximal point: on, off, or (auto) on once the plain loop failed
      if (parameters_.proximal == Proximal::on)
      {
        result.proximal_reason = "on (parameter)";
        run_loop(r, true, result);
      }
      else
      {
        const dealii::Vector<double> start = r;
        run_loop(r, false, result);
        if (parameters_.proximal == Proximal::off)
          result.proximal_reason = "off (parameter)";
        else if (result.converged)
          result.proximal_reason = "off (auto: the plain loop converged)";
        else
        {
          const std::string failure =
            "the plain loop failed after " +
            std::to_string(result.qp_statistics.size()) +
            " QPs: " + result.reason;
          if (parameters_.newton_after_plain_loop &&
              solve_by_newton(start, r, result))
            result.proximal_reason =
              "off (auto: " + failure + "; the Newton method solved it)";
          else
          {
            result.proximal_reason =
              "on (auto: " + failure +
              (parameters_.newton_after_plain_loop ?
                 "; the Newton method failed: " + result.newton.reason :
                 std::string()) +
              ")";
            // from the last iterate whose QP converged (the start if none)
            if (result.last_good.size() == r.size())
              r = result.last_good;
            else
              r = start;
            run_loop(r, true, result);
          }
        }
      }
      result.fclib_error = fclib_error(problem_, r);
      if (result.converged && parameters_.polish &&
          parameters_.model == Model::coulomb_fixed_point &&
          result.fclib_error > coulomb_parameters_.tolerance)
      {
        // a Newton step costs a dense LU where W is dense (n^3), a QP
        // iteration a product (n^2): QPs for a dense W, Newton otherwise
        if (problem_.delassus().dense())
          polish_by_qps(r, result);
        else
          polish_by_newton(r, result);
      }
      result.wall_time = timer.wall_time();
      return result;
    }


    void
    LocalSolver::polish_by_qps(dealii::Vector<double> &r, Result &result) const
    {
      // the plain loop once more from its solution, every QP ten times
      // tighter from the first
      Result                 more;
      dealii::Vector<double> x(r);
      run_loop(x, false, more, true);
      result.iterations += more.iterations;
      result.hessian_products += more.hessian_products;
      result.polish_qps = more.qp_statistics.size();
      result.qp_statistics.insert(result.qp_statistics.end(),
                                  more.qp_statistics.begin(),
                                  more.qp_statistics.end());
      const double error = fclib_error(problem_, x);
      if (more.converged && error < result.fclib_error)
      {
        r                  = x;
        result.fclib_error = error;
      }
    }


    void
    LocalSolver::polish_by_newton(dealii::Vector<double> &r,
                                  Result                 &result) const
    {
      // the loop stops on its own relative criteria; near its solution the
      // Newton method converges in a few steps to the FCLIB error asked for
      NewtonSolver::Parameters newton_parameters =
        newton_to_coulomb_tolerance();
      // from a start this near the solution a weak proximal term at once:
      // the plain method cycled for 20 steps on the singular W of
      // local_problem_test, where one proximal step at sigma 1e-4 (1e-2:
      // 3e-9) takes the error from 1.7e-8 to 1.5e-10 (doc/fclib.md)
      newton_parameters.plain_first = false;
      newton_parameters.sigma = std::max(newton_parameters.sigma_min, 1e-4);
      const NewtonSolver     newton(problem_, newton_parameters);
      dealii::Vector<double> x(r);
      const auto             polish = newton.solve(x);
      result.hessian_products += polish.products;
      result.polish_steps = polish.steps;
      if (polish.converged && polish.fclib_error < result.fclib_error)
      {
        r                  = x;
        result.fclib_error = polish.fclib_error;
      }
    }


    NewtonSolver::Parameters
    LocalSolver::newton_to_coulomb_tolerance() const
    {
      // inside the Coulomb loop's options the Newton method stops where
      // the loop would: at the Coulomb tolerance, on the FCLIB error
      NewtonSolver::Parameters p = parameters_.newton;
      p.tolerance                = coulomb_parameters_.tolerance;
      return p;
    }


    bool
    LocalSolver::solve_by_newton(const dealii::Vector<double> &start,
                                 dealii::Vector<double>       &r,
                                 Result                       &result) const
    {
      const NewtonSolver     newton(problem_, newton_to_coulomb_tolerance());
      dealii::Vector<double> x(start);
      result.newton = newton.solve(x);
      result.hessian_products += result.newton.products;
      if (!result.newton.converged)
        return false;
      r                = x;
      result.converged = true;
      result.reason    = result.newton.reason;
      return true;
    }


    /**
     * The state of one run_loop(): the loop's kind, its limits, the current
     * slip bounds (or De Saxce's shift) psi, the QP tolerance of the inexact
     * fixed point, rho, and the proximal extrapolation's iterates.
     */
    struct LocalSolver::Loop
    {
      bool         proximal;
      double       lambda_max;
      double       rho;
      unsigned int max_iterations;
      /// auto: a plain QP that stalls is cut short (the proximal loop
      /// takes over)
      unsigned int qp_iteration_limit;
      bool         desaxce;
      bool         coulomb_loop;
      /// a proximal term or a non-symmetric W: r solves a perturbed problem
      bool stepping;
      /// Nesterov extrapolation of the proximal centers
      bool                extrapolate;
      std::vector<double> psi;
      /// the first Coulomb iterate is the bonded one (no slip bounds)
      bool   bonded       = false;
      bool   first_change = false;
      double final_tolerance;
      double tolerance;
      double q_norm;
      /// consecutive iterations in which the change grew
      unsigned int           growing = 0;
      dealii::Vector<double> previous, step;
      /// per iterate: the change of psi (Coulomb) or the perturbation
      std::vector<double> measure;
      /// the last iterate r^k, the one before, Nesterov's t_k (1: no
      /// momentum; a restart sets it back)
      dealii::Vector<double> iterate, before;
      double                 t = 1.;
    };


    unsigned int
    LocalSolver::qp_iteration_limit(const Loop &loop) const
    {
      // the bonded QP (no slip bound) is where a singular W with a load
      // along a free tangential direction shows: unbounded below, it never
      // converges
      if (loop.bonded && !loop.proximal &&
          parameters_.proximal == Proximal::automatic)
        return std::min(loop.qp_iteration_limit,
                        parameters_.auto_bonded_qp_max_iterations);
      return loop.qp_iteration_limit;
    }


    void
    LocalSolver::run_loop(dealii::Vector<double> &r,
                          const bool              proximal,
                          Result                 &result,
                          const bool              polish) const
    {
      Loop loop = start_loop(r, proximal, polish, result);
      for (unsigned int it = 0;; ++it)
      {
        if (loop.extrapolate)
          extrapolate_center(loop, r);
        loop.previous = r;
        if (!record(solve_qp(r,
                             loop.bonded ? nullptr : &loop.psi,
                             loop.rho * loop.lambda_max,
                             loop.tolerance,
                             qp_iteration_limit(loop)),
                    result))
        {
          if (retry_with_stronger_rho(loop, it, r, result))
            continue;
          report_qp_failure(loop, it, result);
          break;
        }
        const unsigned int qp_iterations =
          result.qp_statistics.back().iterations;
        result.last_good = r;
        if (!loop.coulomb_loop && !loop.stepping)
        {
          result.converged = true;
          result.reason    = "converged";
          break;
        }
        const double perturbation =
          loop.stepping ? proximal_perturbation(loop, r, result) : 0.;
        const double change =
          loop.coulomb_loop ? update_slip_bounds(loop, r, result) : 0.;
        if (converged_or_non_finite(loop, change, perturbation, result))
          break;
        adapt_tolerance_and_rho(loop,
                                std::max(change, perturbation),
                                qp_iterations,
                                result);
        if (diverged_or_exhausted(loop, it, change, perturbation, result))
          break;
      }
    }


    LocalSolver::Loop
    LocalSolver::start_loop(const dealii::Vector<double> &r,
                            const bool                    proximal,
                            const bool                    polish,
                            Result                       &result) const
    {
      // rho is relative to lambda_max(W_s); with the contact scaling only
      // lambda_max(S W_s S) is known so far
      if (proximal && lambda_max_ == 0)
      {
        lambda_max_ = estimate_lambda_max(
          [this](dealii::Vector<double> &dst, const dealii::Vector<double> &src)
          { problem_.delassus().symmetric_vmult(dst, src); },
          result);
      }
      Loop loop;
      loop.proximal    = proximal;
      loop.lambda_max  = lambda_max_;
      result.proximal  = proximal;
      result.converged = false;
      result.reason.clear();
      loop.rho            = proximal ? parameters_.rho : 0.;
      loop.max_iterations = proximal ?
                              std::max(coulomb_parameters_.max_iterations,
                                       parameters_.proximal_max_iterations) :
                              coulomb_parameters_.max_iterations;
      loop.qp_iteration_limit =
        (!proximal && parameters_.proximal == Proximal::automatic) ?
          parameters_.auto_plain_qp_max_iterations :
          qp_parameters_.max_iterations;

      bool has_friction = false;
      for (const double mu : problem_.mu())
        has_friction = has_friction || mu > 0;
      loop.desaxce = parameters_.model == Model::desaxce_fixed_point;
      loop.coulomb_loop =
        (parameters_.model == Model::coulomb_fixed_point || loop.desaxce) &&
        has_friction;
      loop.stepping    = proximal || asymmetric_;
      loop.extrapolate = proximal && parameters_.extrapolation;

      // cold start: bonded or frictionless first iterate (bonded as in
      // contact::ContactSolver); warm start: bounds from the given r
      if (loop.desaxce)
      {
        // the shift of the start (0 from a cold start: the cone relaxation)
        loop.psi = r.linfty_norm() > 0 ?
                     desaxce_shift(r) :
                     std::vector<double>(problem_.n_contacts(), 0.);
        set_shift(loop.psi);
      }
      else if (r.linfty_norm() > 0)
        loop.psi = slip_bounds(r);
      else if (parameters_.first == FirstIterate::bonded)
        loop.bonded = true;
      else
        loop.psi.assign(problem_.n_contacts(), 0.);
      loop.first_change = r.linfty_norm() == 0;

      // inexact fixed point: the QP tolerance follows the loop's progress
      loop.final_tolerance = qp_parameters_.tolerance * (polish ? 0.1 : 1.);
      loop.tolerance       = loop.final_tolerance;
      if (parameters_.inexact && (loop.coulomb_loop || loop.stepping) &&
          !polish)
        loop.tolerance =
          std::max(loop.final_tolerance, parameters_.initial_qp_tolerance);
      loop.q_norm = problem_.q().l2_norm();
      if (!(loop.q_norm > 0))
        loop.q_norm = 1;
      return loop;
    }


    std::vector<double>
    LocalSolver::desaxce_shift(const dealii::Vector<double> &x) const
    {
      const unsigned int     dim = problem_.spacedim();
      dealii::Vector<double> u;
      problem_.velocity(u, x);
      std::vector<double> s(problem_.n_contacts());
      for (unsigned int i = 0; i < s.size(); ++i)
      {
        double t = 0;
        for (unsigned int k = 1; k < dim; ++k)
          t += u(dim * i + k) * u(dim * i + k);
        s[i] = problem_.mu()[i] * std::sqrt(t);
      }
      return s;
    }


    void
    LocalSolver::set_shift(const std::vector<double> &s) const
    {
      const unsigned int dim = problem_.spacedim();
      shift_.reinit(problem_.size());
      for (unsigned int i = 0; i < s.size(); ++i)
        shift_(dim * i) = s[i];
    }


    std::vector<double>
    LocalSolver::slip_bounds(const dealii::Vector<double> &x) const
    {
      const unsigned int  dim = problem_.spacedim();
      std::vector<double> psi(problem_.n_contacts());
      for (unsigned int i = 0; i < psi.size(); ++i)
        psi[i] = problem_.mu()[i] * std::max(x(dim * i), 0.);
      return psi;
    }


    bool
    LocalSolver::record(const qp::SolverStatistics &s, Result &result)
    {
      result.qp_statistics.push_back(s);
      result.iterations += s.iterations;
      result.hessian_products += s.n_hessian_products;
      return s.converged();
    }


    void
    LocalSolver::extrapolate_center(Loop &loop, dealii::Vector<double> &r) const
    {
      // the center (and start) y = r^k + beta (r^k - r^{k-1}); the QP is
      // then solved around y, and r^{k+1} solves the problem exactly for q
      // perturbed by (rho I + W_a)(r^{k+1} - y)
      loop.iterate = r;
      if (loop.before.size() == r.size() && loop.t > 1.)
      {
        const double t_next = 0.5 * (1. + std::sqrt(1. + 4. * loop.t * loop.t));
        const double beta   = (loop.t - 1.) / t_next;
        r.sadd(1. + beta, -beta, loop.before);
        loop.t = t_next;
      }
      else
        loop.t = 0.5 * (1. + std::sqrt(5.)); // t_1 from t_0 = 1
      loop.before = loop.iterate;
    }


    bool
    LocalSolver::retry_with_stronger_rho(Loop                   &loop,
                                         const unsigned int      it,
                                         dealii::Vector<double> &r,
                                         Result                 &result) const
    {
      // a proximal QP that does not converge: stronger proximal term, the
      // QP again from the previous iterate
      if (!(loop.proximal && parameters_.adaptive_rho &&
            loop.rho < parameters_.rho_max && it + 1 < loop.max_iterations))
        return false;
      r      = loop.extrapolate ? loop.iterate : loop.previous;
      loop.t = 1.; // and no momentum
      loop.rho =
        std::min(loop.rho * parameters_.rho_factor, parameters_.rho_max);
      result.rhos.push_back(loop.rho);
      return true;
    }


    void
    LocalSolver::report_qp_failure(const Loop        &loop,
                                   const unsigned int it,
                                   Result            &result) const
    {
      const std::string where =
        it == 0 ? (loop.coulomb_loop ? " in the first Coulomb iterate" : "") :
                  " in iteration " + std::to_string(it + 1);
      const qp::SolverStatistics &s = result.qp_statistics.back();
      std::ostringstream          message;
      message << "QP solver " << s.solver << " did not converge" << where
              << ": " << qp::to_string(s.reason) << " after " << s.iterations
              << " iterations, criterion " << s.final_criterion
              << " (tolerance " << s.tolerance << ")";
      if (loop.proximal)
        message << ", proximal rho " << loop.rho << " lambda_max";
      result.reason = message.str();
    }


    double
    LocalSolver::proximal_perturbation(Loop                         &loop,
                                       const dealii::Vector<double> &r,
                                       Result &result) const
    {
      // r solves the problem exactly for q + rho (r - r^k) + W_a (r - r^k)
      loop.step = r;
      loop.step -= loop.previous;
      dealii::Vector<double> shift(loop.step.size());
      if (asymmetric_)
        problem_.delassus().antisymmetric_vmult(shift, loop.step);
      shift.add(loop.rho * loop.lambda_max, loop.step);
      const double perturbation = shift.l2_norm() / loop.q_norm;
      result.perturbations.push_back(perturbation);
      // gradient restart: the step r^{k+1} - y turns back against the last
      // move r^{k+1} - r^k
      if (loop.extrapolate)
      {
        dealii::Vector<double> move(r);
        move -= loop.iterate;
        if (loop.step * move < 0)
          loop.t = 1.;
      }
      return perturbation;
    }


    double
    LocalSolver::update_slip_bounds(Loop                         &loop,
                                    const dealii::Vector<double> &r,
                                    Result                       &result) const
    {
      const std::vector<double> old = loop.psi;
      loop.psi = loop.desaxce ? desaxce_shift(r) : slip_bounds(r);
      if (loop.desaxce)
        set_shift(loop.psi);
      double change = 1.;
      if ((!loop.first_change || loop.desaxce) && !loop.bonded)
      {
        double difference = 0, norm = 0;
        for (unsigned int i = 0; i < loop.psi.size(); ++i)
        {
          difference += std::pow(loop.psi[i] - old[i], 2);
          norm += loop.psi[i] * loop.psi[i];
        }
        change = contact::CoulombFixedPoint::relative_change(difference, norm);
      }
      loop.bonded       = false;
      loop.first_change = false;
      result.coulomb_changes.push_back(change);
      return change;
    }


    bool
    LocalSolver::converged_or_non_finite(Loop        &loop,
                                         const double change,
                                         const double perturbation,
                                         Result      &result) const
    {
      if (!std::isfinite(change) || !std::isfinite(perturbation))
      {
        result.reason = "Coulomb/proximal loop: non-finite iterate";
        return true;
      }
      const double progress = std::max(change, perturbation);
      loop.measure.push_back(loop.coulomb_loop ? change : perturbation);
      if (progress <= coulomb_parameters_.tolerance &&
          loop.tolerance <= loop.final_tolerance)
      {
        result.converged = true;
        result.reason    = "converged";
        return true;
      }
      return false;
    }


    void
    LocalSolver::adapt_tolerance_and_rho(Loop              &loop,
                                         const double       progress,
                                         const unsigned int qp_iterations,
                                         Result            &result) const
    {
      if (parameters_.inexact)
        loop.tolerance =
          progress <= coulomb_parameters_.tolerance ?
            loop.final_tolerance :
            std::max(loop.final_tolerance,
                     std::min(loop.tolerance,
                              parameters_.qp_tolerance_factor * progress));
      // rho: weaker after a cheap QP (faster loop), stronger after an
      // expensive one (better conditioned QPs)
      if (loop.proximal && parameters_.adaptive_rho &&
          qp_iterations <= parameters_.rho_decrease_below)
        loop.rho =
          std::max(loop.rho / parameters_.rho_factor, parameters_.rho_min);
      else if (loop.proximal && parameters_.adaptive_rho &&
               qp_iterations > parameters_.rho_increase_above)
        loop.rho =
          std::min(loop.rho * parameters_.rho_factor, parameters_.rho_max);
      if (loop.proximal)
        result.rhos.push_back(loop.rho);
    }


    bool
    LocalSolver::diverged_or_exhausted(Loop              &loop,
                                       const unsigned int it,
                                       const double       change,
                                       const double       perturbation,
                                       Result            &result) const
    {
      // (damped by a proximal term, the changes need not decrease
      // monotonically: no divergence test then)
      const std::vector<double> &measure = loop.measure;
      if (loop.coulomb_loop && !loop.proximal && measure.size() > 1 &&
          measure.back() > measure[measure.size() - 2])
        ++loop.growing;
      else
        loop.growing = 0;
      if (loop.growing >= coulomb_parameters_.divergence_window)
      {
        result.reason =
          std::string(loop.coulomb_loop ? "Coulomb fixed point" :
                                          "lagged-asymmetry loop") +
          " diverged (the change grew in " + std::to_string(loop.growing) +
          " consecutive iterations)";
        return true;
      }
      if (it + 1 >= loop.max_iterations)
      {
        std::ostringstream message;
        message << (loop.coulomb_loop ? "Coulomb fixed point" :
                                        "proximal / lagged-asymmetry loop")
                << (loop.proximal ? " (proximal)" : "")
                << ": maximum iterations (" << loop.max_iterations
                << ") reached, relative change of psi " << change
                << ", perturbation of q " << perturbation;
        result.reason = message.str();
        return true;
      }
      return false;
    }
  } // namespace fclib
} // namespace dualcontact
