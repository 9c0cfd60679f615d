#include <qp/active_set_iteration.h>
#include <qp/kkt_residuals.h>
#include <qp/vector_helpers.h>
#include <qp/vector_kernels.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <vector>

namespace dualcontact
{
  namespace qp
  {
    namespace
    {
      constexpr double infinity = std::numeric_limits<double>::infinity();

      // Curvature p'Ap below this fraction of lambda_max ||p||^2 counts as
      // zero: exact zeros of a singular A come out of a product as
      // rounding noise of that size.
      constexpr double curvature_threshold = 1e-13;

      // compute_kkt_residuals() with the gradient g = A x - b already known
      // (the one a converged solve has just verified by a product): no
      // product for the KKT report when x is feasible to rounding (then
      // the gradient at P(x) differs from g by rounding only).  A short QP
      // of a loop (fclib's Coulomb fixed point: 5-30 iterations) would
      // otherwise spend a tenth of its products on the report.
      template <typename VectorType>
      KKTResiduals
      kkt_from_gradient(const Problem<VectorType> &problem,
                        const VectorType          &x,
                        const VectorType          &g)
      {
        if (problem.equality || !problem.constraints ||
            problem.constraints->feasibility_violation(x) >
              1e-14 * internal::norm(x))
          return compute_kkt_residuals(problem, x);
        KKTResiduals r;
        r.feasibility = problem.constraints->feasibility_violation(x);
        VectorType gp(x);
        problem.constraints->projected_gradient(x, g, gp);
        r.stationarity    = internal::norm(gp);
        r.complementarity = problem.constraints->complementarity(x, g);
        return r;
      }
    } // namespace


    template <typename VectorType>
    ActiveSetIteration<VectorType>::ActiveSetIteration(
      ActiveSetSolver<VectorType> &solver,
      const Problem<VectorType>   &problem,
      VectorType                  &x)
        : solver(solver)
        , prm(solver.prm)
        , name(solver.solver_name)
        , variant(solver.variant)
        , problem(problem)
        , x(x)
        , gradient_given(problem.start_gradient &&
                         problem.start_gradient->size() == x.size())
        , g(solver.g)
        , p(solver.p)
        , Ap(solver.Ap)
        , phi(solver.phi)
        , work(solver.work)
    {
      AssertThrow(!problem.equality,
                  dealii::ExcMessage(
                    name + " does not handle equality constraints; wrap it "
                           "in SMALSE-M"));
      AssertThrow(!variant.bounds_only || !problem.constraints ||
                    problem.constraints->only_bounds_and_boxes(),
                  dealii::ExcMessage(
                    name + " accepts only bound and box constraints; use "
                           "mpgp, mpgp-bb or mwpgp for discs, ellipses and "
                           "cones"));
      // x0 before start() projects it (start_gradient() compares)
      if (gradient_given)
      {
        solver.x_given.reinit(x, true);
        solver.x_given.equ(1., x);
      }

      stats = solver.start(problem, x);

      set_ptr = problem.constraints;
      if (!set_ptr)
      {
        auto empty = std::make_shared<SeparableSet<VectorType>>();
        empty->finalize(problem.b);
        set_ptr = empty;
      }
      set = set_ptr.get();

      lambda_max = solver.lambda_max(problem, stats);
      alpha_bar  = stats.alpha_bar;
      weak       = variant.test == ActiveSetVariant::Test::weak_reduced;
      bb_alpha   = alpha_bar;

      for (VectorType *v : {&g, &p, &Ap, &phi, &work})
        v->reinit(x, true);
      if (variant.barzilai_borwein)
      {
        x_prev.reinit(x);
        g_prev.reinit(x);
      }
      // MPGP-BB too: its BB expansion is then the fall-back when the
      // projected CG step does not lower the cost below the half-step's
      projected_cg = prm.expansion == "projected-cg" && !weak;

      // preconditioning in face changes only the CG steps on the free set
      // (active blocks stay fixed: apply_preconditioner() zeroes them), so
      // MPGP and MPGP-BB take it as MPRGP does; the preconditioned release
      // replaces MPRGP's proportioning step and stays MPRGP's
      preconditioned = prm.preconditioner != "none" && !weak;
      release_preconditioned =
        preconditioned &&
        variant.step == ActiveSetVariant::Step::proportioning &&
        prm.proportioning_step == "preconditioned";
      if (preconditioned)
      {
        mask.reinit(x);
        built_mask.reinit(x);
        z.reinit(x);
        if (prm.preconditioner == "jacobi")
        {
          AssertThrow(problem.diagonal && problem.diagonal->size() == x.size(),
                      dealii::ExcMessage(
                        name + ": Preconditioner = jacobi needs the diagonal "
                               "of the Hessian (Problem::diagonal)"));
        }
        else
        {
          AssertThrow(static_cast<bool>(problem.free_set_preconditioner),
                      dealii::ExcMessage(
                        name + ": Preconditioner = " + prm.preconditioner +
                        " needs a free-set preconditioner factory "
                        "(Problem::free_set_preconditioner): FreeSetAMG is "
                        "one for a serial dealii::SparseMatrix and "
                        "dealii::Vector<double> (qpsolve builds it); there "
                        "is none for distributed vectors, supply your own "
                        "or use jacobi"));
        }
      }
    }


    // 1/2 y'Ay - b'y from the gradient gy = Ay - b: 1/2 y'(gy - b)
    template <typename VectorType>
    double
    ActiveSetIteration<VectorType>::cost_at(const VectorType &y,
                                            const VectorType &gy) const
    {
      return internal::cost(y, gy, problem.b);
    }


    // gy := gy - b (gy holds A y) and the cost at y in one pass
    template <typename VectorType>
    double
    ActiveSetIteration<VectorType>::residual_and_cost(const VectorType &y,
                                                      VectorType &gy) const
    {
      VectorKernels::Lanes s;
      VectorKernels::residual_cost(
        y.locally_owned_size(), y.begin(), problem.b.begin(), gy.begin(), s);
      return 0.5 * internal::sum(s.total(), y);
    }


    // g := A x - b, and f
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::recompute_gradient()
    {
      solver.apply_hessian(problem, g, x, stats);
      f              = residual_and_cost(x, g);
      exact_gradient = true;
    }


    // the stopping criterion from fresh norms at x (every assignment to
    // norms has ||phi|| and ||beta||, MwPGP's also ||beta~||)
    template <typename VectorType>
    double
    ActiveSetIteration<VectorType>::criterion_value()
    {
      if (prm.stopping_criterion == StoppingCriterion::projected)
        return std::sqrt(norms.free_sq + norms.chopped_sq);
      if (prm.stopping_criterion == StoppingCriterion::reduced_projected &&
          weak)
        return std::sqrt(norms.free_sq + norms.reduced_chopped_sq);
      return solver.criterion(problem, x, g, stats);
    }


    // phi_out := phi(x), norms := the gradient norms at x; returns the
    // absolute stopping criterion
    template <typename VectorType>
    double
    ActiveSetIteration<VectorType>::refresh(VectorType &phi_out)
    {
      if (weak)
      {
        set->free_gradient(x, g, phi_out);
        norms = set->reduced_gradient_norms(x, g, alpha_bar);
      }
      else
        norms = set->free_gradient_and_norms(x, g, phi_out);
      return criterion_value();
    }


    // the proportionality test: Gamma (MPRGP, MPGP) or MwPGP's weak test
    template <typename VectorType>
    bool
    ActiveSetIteration<VectorType>::proportional() const
    {
      if (weak)
        return 2. * prm.mwpgp.delta *
                 (norms.free_sq + norms.reduced_chopped_sq) <=
               norms.free_sq;
      return norms.chopped_sq <= prm.gamma * prm.gamma * norms.free_sq;
    }


    // the start gradient: given, given and corrected for the few unknowns
    // the projection moved (columns of A), or a product
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::start_gradient()
    {
      bool                     use_given = false;
      std::vector<std::size_t> moved;
      VectorType              &x_given = solver.x_given;
      if (gradient_given)
      {
        double           *dv = x_given.begin();
        const double     *xv = x.begin();
        const std::size_t n  = x.locally_owned_size();
        // a move by rounding (the projection of a point on a curved
        // boundary rescales it by radius / norm again) is no move: the
        // given gradient is then as exact as a product's
        const double rounding = 8. * std::numeric_limits<double>::epsilon();
        for (std::size_t i = 0; i < n; ++i)
        {
          dv[i] = xv[i] - dv[i]; // x_given := the move d
          if (std::abs(dv[i]) > rounding * std::abs(xv[i]))
            moved.push_back(i);
          else
            dv[i] = 0.;
        }
        // a quarter of a product at most (the columns are not blocked)
        const double n_moved = internal::sum(double(moved.size()), x);
        use_given =
          n_moved == 0. || (problem.hessian_add_sparse &&
                            4. * n_moved <= static_cast<double>(x.size()));
      }
      if (use_given)
      {
        g.equ(1., *problem.start_gradient);
        if (!moved.empty())
          problem.hessian_add_sparse(g, x_given, moved);
        f              = cost_at(x, g);
        exact_gradient = true;
      }
      else
        recompute_gradient();
    }


    // MPGP-BB: the BB length from the last iterate difference s = x_k -
    // x_{k-1}, y = g_k - g_{k-1} = A s (no extra product); one pass: s's,
    // s'y, and x_prev := x, g_prev := g
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::barzilai_borwein_length()
    {
      bb_alpha = alpha_bar;
      VectorKernels::Lanes ss, sy;
      VectorKernels::step_differences(x.locally_owned_size(),
                                      x.begin(),
                                      g.begin(),
                                      x_prev.begin(),
                                      g_prev.begin(),
                                      true,
                                      ss,
                                      sy);
      const double local[2] = {ss.total(), sy.total()};
      if (stats.iterations > 1)
      {
        double global[2];
        dealii::Utilities::MPI::sum(dealii::ArrayView<const double>(local, 2),
                                    internal::communicator(x),
                                    dealii::ArrayView<double>(global, 2));
        if (global[1] > 0. && std::isfinite(global[0] / global[1]))
          bb_alpha = global[0] / global[1];
      }
    }


    // A proportional iterate: along p the CG step if it stays feasible,
    // else the feasible half-step and an expansion (CG restarts)
    template <typename VectorType>
    bool
    ActiveSetIteration<VectorType>::conjugate_gradient_or_half_step()
    {
      if (preconditioned && restart_pending)
      {
        // restart: p := z = M_F^{-1} phi (p holds phi)
        update_preconditioner();
        apply_preconditioner(p, z);
        p.swap(z);
        direction_valid = false;
      }
      restart_pending = false;
      solver.apply_hessian(problem, Ap, p, stats);
      // p'Ap, p'p, g'p (= phi'p, p lives on the free set) in one pass over
      // the local entries, summed in eight lanes by index (VectorKernels);
      // when p came from conjugate_direction(), p'p, g'p and the largest
      // feasible step from there (summed run by run, in the set's lanes)
      // and only p'Ap here
      std::array<double, 3> d;
      if (direction_valid)
        d = {{internal::dot(p, Ap), direction.pp, direction.gp}};
      else
        d = internal::dots(p, Ap, g);
      const double pAp = d[0], pp = d[1], gp = d[2];
      const double alpha_f =
        direction_valid ? direction.max_step : set->max_feasible_step(x, p);
      direction_valid = false;
      double alpha_cg;
      if (!step_along(pAp,
                      pp,
                      gp,
                      alpha_f,
                      "non-finite p'Ap, p'p or g'p in a CG step",
                      "p'Ap",
                      "a feasible descent ray",
                      alpha_cg))
        return false;
      if (alpha_cg <= alpha_f)
        return conjugate_gradient_step(alpha_cg, pAp, gp);
      half_step_and_expansion(alpha_f, alpha_cg, pAp, gp);
      return true;
    }


    // The minimizing step along a direction d from d'Ad, d'd and g'd:
    // alpha = g'd / d'Ad where the curvature is positive, infinity where it
    // is zero (up to curvature_threshold).  Returns false with stats'
    // reason and message on a non-finite value, on negative curvature
    // (A not positive semidefinite) and on zero curvature along a descent
    // direction no bound cuts (alpha_f infinite: MPRGPS' unboundedness
    // test); @p where, @p curvature and @p ray name the step, d'Ad and d
    // in those messages.
    template <typename VectorType>
    bool
    ActiveSetIteration<VectorType>::step_along(const double       dAd,
                                               const double       dd,
                                               const double       gd,
                                               const double       alpha_f,
                                               const std::string &where,
                                               const std::string &curvature,
                                               const std::string &ray,
                                               double            &alpha)
    {
      if (!std::isfinite(dAd + dd + gd))
      {
        stats.reason  = ConvergenceReason::non_finite;
        stats.message = where;
        return false;
      }
      if (dAd < -curvature_threshold * lambda_max * dd)
      {
        stats.reason  = ConvergenceReason::breakdown;
        stats.message = "negative curvature " + curvature + " = " +
                        std::to_string(dAd) +
                        ": the Hessian is not positive semidefinite";
        return false;
      }
      alpha = dAd > curvature_threshold * lambda_max * dd ? gd / dAd : infinity;
      if (alpha == infinity && alpha_f == infinity && gd > 0.)
      {
        stats.reason  = ConvergenceReason::unbounded;
        stats.message = "zero curvature along " + ray +
                        " (MPRGPS test): the cost is unbounded below";
        return false;
      }
      return true;
    }


    // x := x - alpha_cg p, the new conjugate direction (PCG on the free
    // set with a preconditioner in face)
    template <typename VectorType>
    bool
    ActiveSetIteration<VectorType>::conjugate_gradient_step(
      const double alpha_cg,
      const double pAp,
      const double gp)
    {
      f -= 0.5 * alpha_cg * gp;
      ++stats.n_cg;
      exact_gradient = false;
      double beta_cg;
      if (preconditioned)
      {
        // PCG on the free set: z = M_F^{-1} phi, beta = z'Ap / p'Ap
        double phi_Ap = 0.;
        norms         = set->cg_step(x, g, p, Ap, alpha_cg, phi_Ap);
        value         = criterion_value();
        set->free_gradient(x, g, phi);
        apply_preconditioner(phi, z);
        beta_cg = internal::dot(z, Ap) / pAp;
      }
      else
      {
        // x, g, norms (MwPGP: with the reduced chopped gradient's) and
        // phi'Ap in one pass; the new direction p = phi - beta p with its
        // feasible step in a second
        double phi_Ap = 0.;
        norms =
          set->cg_step(x, g, p, Ap, alpha_cg, phi_Ap, weak ? alpha_bar : 0.);
        value   = criterion_value();
        beta_cg = phi_Ap / pAp;
      }
      if (!std::isfinite(beta_cg))
      {
        stats.record_criterion(value / stats.norm_b, solver.elapsed());
        stats.final_criterion = value / stats.norm_b;
        stats.reason          = ConvergenceReason::non_finite;
        stats.message         = "non-finite CG coefficient";
        return false;
      }
      if (preconditioned)
        p.sadd(-beta_cg, 1., z);
      else
      {
        direction       = set->conjugate_direction(x, g, beta_cg, p);
        direction_valid = true;
      }
      return true;
    }


    // the feasible half-step, then the expansion (or the projected-CG
    // trials in its place); CG restarts
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::half_step_and_expansion(
      const double alpha_f,
      const double alpha_cg,
      const double pAp,
      const double gp)
    {
      ++stats.n_half_steps;
      const double f_half   = f - alpha_f * gp + 0.5 * alpha_f * alpha_f * pAp;
      bool         expanded = false;
      if (projected_cg && alpha_cg < infinity)
        expanded = projected_cg_expansion(alpha_f, alpha_cg, f_half);
      if (!expanded)
      {
        set->feasible_step(x, p, alpha_f);
        g.add(-alpha_f, Ap);
        exact_gradient = false; // until the expansion's product
        f              = f_half;
        expansion();
      }
      value           = refresh(p);
      restart_pending = true;
    }


    // The whole CG step from x, projected: work := P(x - t p), phi := A
    // work - b, for t = alpha_cg and (with `projected_cg_trials` > 1) t =
    // alpha_f + (alpha_cg - alpha_f) 2^-k; the trial of least cost is kept
    // if it lowers the cost below the half-step's.  (With a preconditioner
    // in face the whole step overshoots far into the obstacle, and the
    // first trial below the half-step's cost activates too much, which
    // proportioning must undo.)  Returns whether a trial was taken.
    template <typename VectorType>
    bool
    ActiveSetIteration<VectorType>::projected_cg_expansion(
      const double alpha_f,
      const double alpha_cg,
      const double f_half)
    {
      bool       expanded     = false;
      double     f_best       = f_half;
      const auto trial_length = [&](const unsigned int k)
      {
        return k == 0 ?
                 alpha_cg :
                 alpha_f + (alpha_cg - alpha_f) * std::ldexp(1., -int(k));
      };
      // Projected-CG gradient factor: the cost and ||g^P||^2 of every
      // trial, and which one is of least cost
      const bool gradient_choice = prm.projected_cg_gradient_factor > 0.;
      std::vector<double> trial_cost, trial_gradient;
      unsigned int        best_trial = 0;
      for (unsigned int k = 0; k < prm.projected_cg_trials; ++k)
      {
        const double f_cg = projected_trial(work, phi, p, trial_length(k));
        if (gradient_choice)
        {
          const GradientNorms trial_norms = set->gradient_norms(work, phi);
          trial_cost.push_back(f_cg);
          trial_gradient.push_back(trial_norms.free_sq +
                                   trial_norms.chopped_sq);
        }
        if (f_cg <= f_best)
        {
          best_trial = k;
          keep_trial();
          f_best   = f_cg;
          expanded = true;
        }
      }
      if (gradient_choice && expanded)
      {
        // the least cost among the trials below the half-step's cost whose
        // ||g^P|| is within the factor of the least ||g^P|| among them: the
        // least-cost trial of a preconditioned direction activates a band
        // beyond the contact zone, which proportioning releases one grid
        // line per step (doc/benchmarks/membrane.md)
        double least_gradient = infinity;
        for (unsigned int k = 0; k < trial_cost.size(); ++k)
          if (trial_cost[k] <= f_half)
            least_gradient = std::min(least_gradient, trial_gradient[k]);
        const double bound = prm.projected_cg_gradient_factor *
                             prm.projected_cg_gradient_factor * least_gradient;
        unsigned int chosen      = best_trial;
        double       chosen_cost = infinity;
        for (unsigned int k = 0; k < trial_cost.size(); ++k)
          if (trial_cost[k] <= f_half && trial_gradient[k] <= bound &&
              trial_cost[k] < chosen_cost)
          {
            chosen      = k;
            chosen_cost = trial_cost[k];
          }
        if (chosen != best_trial)
        {
          // redo the chosen trial (one more product)
          f_best = projected_trial(x_best, g_best, p, trial_length(chosen));
        }
      }
      if (expanded)
      {
        take_kept_trial(f_best);
        ++stats.n_expansions;
      }
      else
        ++stats.n_fall_back;
      return expanded;
    }


    // Gradient projection x := P(x - alpha d), d = phi or g, in one pass;
    // new g.
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::projection_step(const double alpha)
    {
      set->projected_step(x, g, alpha, variant.expand_with_free_gradient);
      if (problem.constraints)
        ++stats.n_projections;
      recompute_gradient();
      ++stats.n_expansions;
    }


    // The expansion (after a half-step, or MPGP's non-proportional step):
    // fixed length alpha_bar, or Barzilai-Borwein with a non-monotone
    // safeguard: a BB step is accepted if the cost does not exceed the
    // largest of the costs before the last `mpgp_bb.memory` BB attempts
    // (Grippo-Lampariello-Lucidi), else it is redone with alpha_bar (a
    // fall-back).  Memory 0 = monotone.
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::expansion()
    {
      if (!variant.barzilai_borwein)
      {
        projection_step(alpha_bar);
        return;
      }
      const double alpha = bb_alpha;
      if (alpha == alpha_bar)
      {
        projection_step(alpha_bar);
        return;
      }
      const double f_old = cost_at(x, g);
      recent_costs.push_back(f_old);
      while (recent_costs.size() > std::max(prm.mpgp_bb.memory, 1u))
        recent_costs.pop_front();
      const double reference =
        prm.mpgp_bb.memory == 0 ?
          f_old :
          *std::max_element(recent_costs.begin(), recent_costs.end());
      work.equ(1., x);
      phi.equ(1., g); // keep g; phi is free here
      projection_step(alpha);
      if (f <= reference)
      {
        ++stats.n_bb;
        return;
      }
      // fall back: redo from the saved point with alpha_bar
      x.equ(1., work);
      g.equ(1., phi);
      --stats.n_expansions;
      projection_step(alpha_bar);
      ++stats.n_fall_back;
    }


    // MPRGP's non-proportional step: steepest descent along the chopped
    // gradient beta, cut at the boundary (boxes), or the preconditioned
    // release in its place
    template <typename VectorType>
    bool
    ActiveSetIteration<VectorType>::proportioning_step()
    {
      direction_valid = false;
      set->chopped_gradient(x, g, p);
      solver.apply_hessian(problem, Ap, p, stats);
      const std::array<double, 3> d   = internal::dots(p, Ap, g);
      const double                bAb = d[0], bb = d[1], gb = d[2];
      const double                alpha_f = set->max_feasible_step(x, p);
      double                      alpha_sd;
      if (!step_along(bAb,
                      bb,
                      gb,
                      alpha_f,
                      "non-finite value in a proportioning step",
                      "beta'A beta",
                      "the chopped gradient, which leaves every bound",
                      alpha_sd))
        return false;
      const double alpha = std::min(alpha_sd, alpha_f);
      const bool   released =
        release_preconditioned && preconditioned_release(alpha, gb, bAb);
      if (!released)
      {
        set->feasible_step(x, p, alpha);
        g.add(-alpha, Ap);
        exact_gradient = false;
        f += -alpha * gb + 0.5 * alpha * alpha * bAb;
      }
      ++stats.n_proportioning;
      value           = refresh(p);
      restart_pending = true;
      return true;
    }


    // Preconditioned release (Proportioning step = preconditioned): the
    // chopped gradient beta (in p) names the released set R; the step is
    // the projected PCG step on F u R from x, z = M_{F u R}^{-1} (phi +
    // beta), t0 = g'z / z'Az and t0 2^-k (k < Projected-CG trials), the
    // least cost kept if below the cost after MPRGP's own proportioning
    // step (else that step is taken: MPRGP's convergence argument holds
    // either way).  M_{F u R} is what the next restart needs when the step
    // frees exactly R, so it is no extra setup then.  Returns whether a
    // trial was taken.
    template <typename VectorType>
    bool
    ActiveSetIteration<VectorType>::preconditioned_release(const double alpha,
                                                           const double gb,
                                                           const double bAb)
    {
      bool         released = false;
      const double f_prop   = f - alpha * gb + 0.5 * alpha * alpha * bAb;
      // mask: the active set minus R
      set->active_mask(x, mask);
      {
        double           *mv = mask.begin();
        const double     *bv = p.begin();
        const std::size_t n  = mask.locally_owned_size();
        for (std::size_t i = 0; i < n; ++i)
          if (bv[i] != 0.)
            mv[i] = 0.;
      }
      build_preconditioner();
      // phi := phi + beta (the gradient on F u R), z := M^{-1} of it on
      // F u R
      set->free_gradient(x, g, phi);
      phi += p;
      const Clock::time_point start = Clock::now();
      free_set_inverse(z, phi);
      {
        double           *zv = z.begin();
        const double     *mv = built_mask.begin();
        const std::size_t n  = z.locally_owned_size();
        for (std::size_t i = 0; i < n; ++i)
          if (mv[i] != 0.)
            zv[i] = 0.;
      }
      if (!(internal::dot(phi, z) > 0.))
        z.equ(1., phi);
      ++stats.n_preconditioner_applications;
      stats.preconditioner_apply_time += seconds(start);
      if (Az.size() != x.size())
        Az.reinit(x);
      solver.apply_hessian(problem, Az, z, stats);
      const double gz = internal::dot(g, z), zAz = internal::dot(z, Az);
      if (gz > 0. &&
          zAz > curvature_threshold * lambda_max * internal::dot(z, z))
      {
        const double t0     = gz / zAz;
        double       f_best = f_prop;
        for (unsigned int k = 0; k < prm.projected_cg_trials; ++k)
        {
          const double f_t =
            projected_trial(work, phi, z, std::ldexp(t0, -int(k)));
          if (f_t < f_best)
          {
            keep_trial();
            f_best   = f_t;
            released = true;
          }
        }
        if (released)
        {
          take_kept_trial(f_best);
          ++stats.n_preconditioned_releases;
        }
      }
      return released;
    }


    // g was updated by recurrences (g -= alpha A p); before claiming
    // convergence, check with the true gradient A x - b (one product),
    // which differs when rounding or an inexact operator made the
    // recurrence drift (run() tests again; if that fails, the loop goes on
    // from the true gradient with a CG restart).
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::verify_convergence()
    {
      stats.drop_last_criterion();
      recompute_gradient();
      direction_valid = false;
    }


    template <typename VectorType>
    SolverStatistics
    ActiveSetIteration<VectorType>::run()
    {
      start_gradient();
      bool stop = solver.check_stop(stats, refresh(p), f); // p = phi
      while (!stop)
      {
        ++stats.iterations;
        if (variant.barzilai_borwein)
          barzilai_borwein_length();
        bool go_on;
        if (proportional())
          go_on = conjugate_gradient_or_half_step();
        else if (variant.step == ActiveSetVariant::Step::proportioning)
          go_on = proportioning_step();
        else
        {
          direction_valid = false;
          expansion();
          value           = refresh(p);
          restart_pending = true;
          go_on           = true;
        }
        if (!go_on)
          break;
        stop = solver.check_stop(stats, value, f);
        if (stop && stats.reason == ConvergenceReason::converged &&
            !exact_gradient)
        {
          verify_convergence();
          stop = solver.check_stop(stats, refresh(p), f); // restart: p = phi
          restart_pending = true;
        }
      }
      finish();
      return stats;
    }


    // the KKT report from the verified gradient, kept for the next QP of a
    // loop (Problem::start_gradient), or from a product
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::finish()
    {
      if (exact_gradient)
      {
        stats.wall_time = solver.elapsed();
        stats.kkt       = kkt_from_gradient(problem, x, g);
        solver.last_gradient.swap(g);
        solver.last_gradient_valid = true;
      }
      else
        solver.finish(problem, x, stats);
    }


    template <typename VectorType>
    double
    ActiveSetIteration<VectorType>::seconds(const Clock::time_point start)
    {
      return std::chrono::duration<double>(Clock::now() - start).count();
    }


    // M_F for the free set where `mask` is 0 (rebuilt only if that set
    // changed)
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::build_preconditioner()
    {
      if (have_preconditioner)
      {
        const double     *mv = mask.begin(), *bv = built_mask.begin();
        const std::size_t n       = mask.locally_owned_size();
        double            changed = 0.;
        for (std::size_t i = 0; i < n; ++i)
          if (mv[i] != bv[i])
          {
            changed = 1.;
            break;
          }
        if (internal::max(changed, x) == 0.)
          return;
      }
      const Clock::time_point start = Clock::now();
      if (prm.preconditioner == "jacobi")
      {
        if (!have_preconditioner)
        {
          // M_F = diag(A)_FF; the active entries are zeroed by the
          // caller, so one operator serves every free set
          const double     *dv    = problem.diagonal->begin();
          const std::size_t n     = x.locally_owned_size();
          double            least = infinity;
          for (std::size_t i = 0; i < n; ++i)
            least = std::min(least, dv[i]);
          AssertThrow(internal::min(least, x) > 0.,
                      dealii::ExcMessage(name +
                                         ": Preconditioner = jacobi needs a "
                                         "positive diagonal of the Hessian"));
          const std::shared_ptr<const VectorType> diagonal = problem.diagonal;
          free_set_inverse = [diagonal](VectorType &dst, const VectorType &src)
          {
            const double     *sv = src.begin(), *dv = diagonal->begin();
            double           *ov = dst.begin();
            const std::size_t n  = dst.locally_owned_size();
            for (std::size_t i = 0; i < n; ++i)
              ov[i] = sv[i] / dv[i];
          };
          ++stats.n_preconditioner_setups;
        }
      }
      else
      {
        free_set_inverse = problem.free_set_preconditioner(mask);
        AssertThrow(static_cast<bool>(free_set_inverse),
                    dealii::ExcMessage(
                      name + ": the problem's free-set preconditioner "
                             "factory returned no operator"));
        ++stats.n_preconditioner_setups;
      }
      built_mask.swap(mask);
      have_preconditioner = true;
      stats.preconditioner_setup_time += seconds(start);
    }


    // M_F for the active set at x
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::update_preconditioner()
    {
      set->active_mask(x, mask);
      build_preconditioner();
    }


    // out := M_F^{-1} in restricted to the free set at x (in, out may not
    // alias)
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::apply_preconditioner(const VectorType &in,
                                                         VectorType       &out)
    {
      const Clock::time_point start = Clock::now();
      free_set_inverse(out, in);
      set->zero_active(x, out);
      // safeguard: an operator that is not positive definite on the free
      // set (a broken or non-symmetric M_F) would give a direction that is
      // not a descent direction; use phi itself then
      if (!(internal::dot(in, out) > 0.))
        out.equ(1., in);
      ++stats.n_preconditioner_applications;
      stats.preconditioner_apply_time += seconds(start);
    }


    // The projected trials of the projected-CG expansion and of the
    // preconditioned release: y := P(x - t d), gy := A y - b (a projection
    // and a product); returns the cost at y
    template <typename VectorType>
    double
    ActiveSetIteration<VectorType>::projected_trial(VectorType       &y,
                                                    VectorType       &gy,
                                                    const VectorType &d,
                                                    const double      t)
    {
      y.equ(1., x);
      set->projected_step(y, d, t, false);
      if (problem.constraints)
        ++stats.n_projections;
      solver.apply_hessian(problem, gy, y, stats);
      return residual_and_cost(y, gy);
    }


    // the trial in work, phi becomes the best one so far (x_best, g_best)
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::keep_trial()
    {
      if (x_best.size() != x.size())
      {
        x_best.reinit(x);
        g_best.reinit(x);
      }
      x_best.swap(work);
      g_best.swap(phi);
    }


    // x, g := the kept trial, whose gradient is exact, f := its cost
    template <typename VectorType>
    void
    ActiveSetIteration<VectorType>::take_kept_trial(const double cost)
    {
      x.swap(x_best);
      g.swap(g_best);
      exact_gradient = true;
      f              = cost;
    }


    template class ActiveSetIteration<dealii::Vector<double>>;
    template class ActiveSetIteration<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
