#include <qp/augmented_lagrangian.h>
#include <qp/kkt_residuals.h>
#include <qp/power_iteration.h>
#include <qp/smalse_m.h>
#include <qp/solver_factory.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>

namespace dualcontact
{
  namespace qp
  {
    void
    SMALSEMParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("QP solver");
      prm.enter_subsection("SMALSE-M");
      prm.declare_entry("Penalty factor",
                        "10",
                        dealii::Patterns::Double(0.),
                        "rho = factor * lambda_max(A) (thesis 2.5, which uses "
                        "rho of the order of ||A||). Default 10: on the dual "
                        "contact problems 1 needed several times more outer "
                        "iterations (48 against 13 on inputs/hertz_3d.prm) or "
                        "none converged within the limit.");
      prm.declare_entry("M0",
                        "100",
                        dealii::Patterns::Double(0.),
                        "Initial M of the inner precision control "
                        "||g^P|| <= min(M ||Bx - c||, eta).");
      prm.declare_entry("Eta factor",
                        "0.1",
                        dealii::Patterns::Double(0.),
                        "eta = factor * ||b||.");
      prm.declare_entry("Beta",
                        "0.2",
                        dealii::Patterns::Double(0., 1.),
                        "M := beta M when the augmented Lagrangian did not "
                        "increase enough (in (0, 1)).");
      prm.declare_entry("Maximum outer iterations",
                        "100",
                        dealii::Patterns::Integer(1),
                        "Limit on SMALSE-M outer iterations.");
      prm.declare_entry("Coarse projector",
                        "true",
                        dealii::Patterns::Bool(),
                        "With orthonormal equality rows (the contact duals' "
                        "G~, undecomposed and TFETI): solve the inner QPs "
                        "with the projected Hessian P F P + rho G~'G~, "
                        "P = I - G~'G~ (thesis 3.1), instead of the penalty "
                        "form F + rho G~'G~ (false: the thesis' SMALBE-M "
                        "setting). Other problems are not affected.");
      prm.declare_entry("Projector penalty factor",
                        "automatic",
                        dealii::Patterns::Anything(),
                        "rho = factor * lambda_max(P A P) with the coarse "
                        "projector P (lambda_max(A) where the formulation "
                        "does not know P A P's; `Penalty factor' is used "
                        "without the projector): a number > 0, or "
                        "automatic: the formulation's measured choice; for "
                        "the undecomposed dual's rigid-body modes 10 with "
                        "bounds and boxes, 1 with friction discs and "
                        "ellipses (lib/contact/README.md, "
                        "\"Pseudoinverses\"); for TFETI's coarse space 1 "
                        "in 3D with a floating body, 3 otherwise "
                        "(doc/benchmarks/tfeti.md, \"Pseudoinverses\").");
      prm.declare_entry("Equality tolerance factor",
                        "1",
                        dealii::Patterns::Double(0.),
                        "Converged needs ||Bx - c|| <= factor * Tolerance * "
                        "min(||b||, max(||c||, ||B|| ||x||)).");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    void
    SMALSEMParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("QP solver");
      prm.enter_subsection("SMALSE-M");
      rho_factor                = prm.get_double("Penalty factor");
      m0                        = prm.get_double("M0");
      eta_factor                = prm.get_double("Eta factor");
      beta                      = prm.get_double("Beta");
      max_outer_iterations      = prm.get_integer("Maximum outer iterations");
      equality_tolerance_factor = prm.get_double("Equality tolerance factor");
      coarse_projector          = prm.get_bool("Coarse projector");
      // automatic: 0; not a number, or not positive: -1, which check()
      // reports naming the parameter
      const std::string projector_factor = prm.get("Projector penalty factor");
      if (projector_factor == "automatic")
        projector_penalty_factor = 0.;
      else
      {
        char        *end         = nullptr;
        const double value       = std::strtod(projector_factor.c_str(), &end);
        const bool   whole       = !projector_factor.empty() && *end == '\0';
        projector_penalty_factor = whole && value > 0. ? value : -1.;
      }
      prm.leave_subsection();
      prm.leave_subsection();
      check();
    }


    void
    SMALSEMParameters::check() const
    {
      const auto fail = [](const std::string &name, const std::string &what)
      {
        AssertThrow(false,
                    dealii::ExcMessage("`" + name +
                                       "' in `subsection QP solver / "
                                       "subsection SMALSE-M' " +
                                       what));
      };
      if (!(rho_factor > 0.))
        fail("Penalty factor", "must be > 0");
      if (!(m0 > 0.))
        fail("M0", "must be > 0");
      if (!(eta_factor > 0.))
        fail("Eta factor", "must be > 0");
      if (!(beta > 0. && beta < 1.))
        fail("Beta", "must be in (0, 1)");
      if (max_outer_iterations < 1)
        fail("Maximum outer iterations", "must be >= 1");
      if (!(projector_penalty_factor >= 0.))
        fail("Projector penalty factor", "must be `automatic' or a number > 0");
      if (!(equality_tolerance_factor > 0.))
        fail("Equality tolerance factor", "must be > 0");
    }


    template <typename VectorType>
    SMALSEM<VectorType>::SMALSEM(const SolverParameters  &parameters,
                                 const SMALSEMParameters &smalse_parameters)
        : SolverBase<VectorType>("smalse-m(" + parameters.solver + ")",
                                 parameters)
        , smalse_prm(smalse_parameters)
    {
      smalse_prm.check();
    }


    template <typename VectorType>
    double
    SMALSEM<VectorType>::equality_residual() const
    {
      return last_equality_residual;
    }


    template <typename VectorType>
    const VectorType &
    SMALSEM<VectorType>::multipliers() const
    {
      return lambda;
    }


    namespace
    {
      /// ||g^P(x)|| for the problem's separable set, ||g|| without one
      template <typename VectorType>
      double
      projected_norm(const Problem<VectorType> &problem,
                     const VectorType          &x,
                     const VectorType          &g)
      {
        if (!problem.constraints)
          return g.l2_norm();
        const GradientNorms n = problem.constraints->gradient_norms(x, g);
        return std::sqrt(n.free_sq + n.chopped_sq);
      }
    } // namespace


    template <typename VectorType>
    SolverStatistics
    SMALSEM<VectorType>::solve(const Problem<VectorType> &problem,
                               VectorType                &x)
    {
      const SolverParameters &prm   = this->prm;
      SolverStatistics        stats = this->start(problem, x);
      AssertThrow(problem.equality != nullptr,
                  dealii::ExcMessage("SMALSE-M: the problem has no equality "
                                     "constraints; use the inner solver '" +
                                     prm.solver + "' directly"));
      const EqualityConstraints<VectorType> &eq = *problem.equality;
      AssertThrow(eq.vmult && eq.Tvmult,
                  dealii::ExcMessage("SMALSE-M: B and B' products needed"));

      // lambda_max(A) sets rho
      const bool project = eq.orthonormal_rows && smalse_prm.coarse_projector;
      // lambda_max of what the inner solves see: A, or P A P with the
      // projector where the formulation knows it (P A P + rho B'B has
      // max(lambda_max(P A P), rho))
      const double lmax_A = project && eq.projected_lambda_max > 0. ?
                              eq.projected_lambda_max :
                              this->lambda_max(problem, stats);
      // automatic (0): the factor the formulation measured for its rows
      const double projector_factor = smalse_prm.projector_penalty_factor > 0. ?
                                        smalse_prm.projector_penalty_factor :
                                        eq.projector_penalty_factor;
      const double rho =
        (project ? projector_factor : smalse_prm.rho_factor) * lmax_A;
      AugmentedLagrangian<VectorType> lagrangian(
        problem, project, rho, x, stats);
      Problem<VectorType> inner = lagrangian.inner_problem(lmax_A, prm);

      const double eta           = smalse_prm.eta_factor * stats.norm_b;
      const double tolerance     = prm.tolerance * stats.norm_b;
      double       M             = smalse_prm.m0;
      double       previous_L    = 0.;
      double       norm_residual = lagrangian.equality_residual(x);
      bool         have_previous = false;
      stats.reason               = ConvergenceReason::max_iterations;
      for (unsigned int outer = 0;; ++outer)
      {
        lagrangian.inner_right_hand_side(inner.b);
        const unsigned int iterations_before = stats.iterations;
        if (!solve_inner(
              inner, lagrangian, M, eta, tolerance, x, norm_residual, stats))
          break;
        ++stats.n_outer;
        if (outer_loop_stops(
              problem, lagrangian, outer, x, norm_residual, tolerance, stats))
          break;

        // Step 3 (before step 2, it needs lambda^k): M update
        const double L = lagrangian.value(x);
        if (have_previous &&
            L < previous_L + 0.5 * rho * norm_residual * norm_residual)
          M *= smalse_prm.beta;
        // Deviation with the coarse projector: an inner solve that stopped
        // at its start (its gradient already below M ||Bx - c||) leaves x
        // as it was, and the multiplier update alone grows that gradient
        // by only rho ||Bx - c|| per outer iteration; with the projector's
        // rho = lambda_max(A) a clamped beam in 16 subdomains spent 90
        // outer iterations so (tests/decomposition/tfeti_dual, case G).
        // Tightening M there makes the next inner solve work.
        else if (project && stats.iterations == iterations_before)
          M *= smalse_prm.beta;
        // Step 2: multipliers
        lagrangian.update_multipliers(x);
        previous_L    = L;
        have_previous = true;
      }

      last_equality_residual = lagrangian.equality_residual(x);
      lambda                 = lagrangian.multipliers();
      stats.message += (stats.message.empty() ? "" : "; ") +
                       std::string("equality residual ||Bx - c|| = ") +
                       std::to_string(last_equality_residual) +
                       ", outer iterations " + std::to_string(stats.n_outer) +
                       ", rho = " + std::to_string(rho) +
                       (project ? ", coarse projector" : "");
      this->finish(problem, x, stats);
      report_lagrangian_kkt(problem, lagrangian, x, stats);
      return stats;
    }


    template <typename VectorType>
    bool
    SMALSEM<VectorType>::solve_inner(
      const Problem<VectorType>       &inner,
      AugmentedLagrangian<VectorType> &lagrangian,
      const double                     M,
      const double                     eta,
      const double                     tolerance,
      VectorType                      &x,
      double                          &norm_residual,
      SolverStatistics                &stats) const
    {
      const SolverParameters &prm  = this->prm;
      const double norm_inner_b    = std::max(inner.b.l2_norm(), 1e-300);
      double       inner_tolerance = std::min(M * norm_residual, eta);
      inner_tolerance              = std::max(inner_tolerance, 0.1 * tolerance);
      SolverParameters inner_prm   = prm;
      for (unsigned int attempt = 0; attempt < 3; ++attempt)
      {
        inner_prm.tolerance = std::min(0.5, inner_tolerance / norm_inner_b);
        inner_prm.max_iterations = prm.max_iterations > stats.iterations ?
                                     prm.max_iterations - stats.iterations :
                                     1;
        auto inner_solver        = create<VectorType>(prm.solver, inner_prm);
        const SolverStatistics s = inner_solver->solve(inner, x);
        stats.add_step_counts(s);
        if (s.reason == ConvergenceReason::non_finite ||
            s.reason == ConvergenceReason::unbounded ||
            s.reason == ConvergenceReason::breakdown)
        {
          stats.reason  = s.reason;
          stats.message = "inner solver (" + prm.solver +
                          "): " + to_string(s.reason) + " " + s.message;
          return false;
        }
        norm_residual       = lagrangian.equality_residual(x);
        const double g_norm = s.final_criterion * s.norm_b;
        // condition (2.36) at the new iterate
        const double wanted = std::min(M * norm_residual, eta);
        if (g_norm <= std::max(wanted, 0.1 * tolerance) ||
            stats.iterations >= prm.max_iterations ||
            s.reason != ConvergenceReason::converged)
          break;
        inner_tolerance = std::max(wanted, 0.1 * tolerance);
      }
      return true;
    }


    template <typename VectorType>
    double
    SMALSEM<VectorType>::equality_tolerance(const Problem<VectorType> &problem,
                                            const VectorType          &x,
                                            const double norm_b) const
    {
      // The equality residual is measured against the size of the
      // equality itself, never more loosely than against ||b|| (thesis):
      // tol * min(||b||, max(||c||, ||B|| ||x||)).  Against ||b|| alone a
      // dual contact problem whose ||b|| is dominated by the initial gaps
      // of far-away nodes (a stiff floating body: ||b|| = 1e11 N/m against
      // a weight ||c|| = 1e6 N/m) accepted x = 0, i.e. no contact force
      // holding the body, as converged.  The ||B|| ||x|| term keeps the
      // test relative when c = 0 (a floating body with balanced loads).
      const EqualityConstraints<VectorType> &eq     = *problem.equality;
      const double                           norm_c = eq.c.l2_norm();
      const double norm_B = std::sqrt(std::max(eq.norm_sq, 0.));
      const double size   = std::max(norm_c, norm_B * x.l2_norm());
      return smalse_prm.equality_tolerance_factor * this->prm.tolerance *
             (size > 0. ? std::min(norm_b, size) : norm_b);
    }


    template <typename VectorType>
    bool
    SMALSEM<VectorType>::outer_loop_stops(
      const Problem<VectorType>       &problem,
      AugmentedLagrangian<VectorType> &lagrangian,
      const unsigned int               outer,
      const VectorType                &x,
      const double                     norm_residual,
      const double                     tolerance,
      SolverStatistics                &stats) const
    {
      const SolverParameters &prm = this->prm;
      // the projected gradient of the Lagrangian at (x, lambda + rho (Bx -
      // c)) and the equality residual
      const VectorType &g = lagrangian.gradient(x);
      const double      wanted_residual =
        equality_tolerance(problem, x, stats.norm_b);
      const double criterion = projected_norm(problem, x, g);
      stats.record_criterion(criterion / stats.norm_b, this->elapsed());
      stats.final_criterion = std::max(criterion,
                                       norm_residual * tolerance /
                                         std::max(wanted_residual, 1e-300)) /
                              stats.norm_b;
      if (!std::isfinite(criterion) || !std::isfinite(norm_residual))
      {
        stats.reason  = ConvergenceReason::non_finite;
        stats.message = "non-finite gradient or equality residual";
        return true;
      }
      if (criterion <= tolerance && norm_residual <= wanted_residual)
      {
        stats.reason = ConvergenceReason::converged;
        return true;
      }
      if (stats.iterations >= prm.max_iterations)
      {
        stats.reason  = ConvergenceReason::max_iterations;
        stats.message = "iteration limit " +
                        std::to_string(prm.max_iterations) +
                        " reached (inner iterations)";
        return true;
      }
      if (outer + 1 >= smalse_prm.max_outer_iterations)
      {
        stats.reason  = ConvergenceReason::max_iterations;
        stats.message = "outer iteration limit " +
                        std::to_string(smalse_prm.max_outer_iterations) +
                        " reached";
        return true;
      }
      return false;
    }


    template <typename VectorType>
    void
    SMALSEM<VectorType>::report_lagrangian_kkt(
      const Problem<VectorType>       &problem,
      AugmentedLagrangian<VectorType> &lagrangian,
      const VectorType                &x,
      SolverStatistics                &stats) const
    {
      // stationarity of the Lagrangian, not of the plain gradient; its
      // gradient uses lambda + rho(Bx - c) = the updated multiplier
      const VectorType &g = lagrangian.gradient(x);
      --stats.n_hessian_products; // the report's product is not work
      stats.kkt.stationarity = projected_norm(problem, x, g);
      // likewise complementarity: with the plain gradient Ax - b the bound
      // multiplier estimates -g_j miss B'lambda and are wrong wherever a
      // bound is inactive (a floating body's contact nodes in contact)
      if (problem.constraints)
        stats.kkt.complementarity = problem.constraints->complementarity(x, g);
      if (stats.reason == ConvergenceReason::converged &&
          !(stats.final_criterion <= this->prm.tolerance))
        stats.reason = ConvergenceReason::stagnation;
    }


    template class SMALSEM<dealii::Vector<double>>;
    template class SMALSEM<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
