// MPRGP with preconditioning in face (parameter `Preconditioner`, Dostal
// 2009, sec. 5.10).
//  1. Planted bound / box / bound+box QPs (dense A, kappa 1e3): solved to
//     ||g^P|| <= 1e-10 ||b|| with `jacobi` and with a factory that returns
//     the exact inverse of A_FF (Cholesky of the free-set block, rebuilt
//     for every active set); checks x = x*, KKT residuals, the statistics
//     (setups, applications), and that the exact M_F needs no more CG
//     steps than active-set changes allow.
//  2. Planted sparse QP on a 5-point Laplacian with a badly scaled
//     diagonal (A = D L D, D_ii in [1, 10]): the contact zone is a block
//     of the grid.  none, jacobi and amg (FreeSetAMG, Trilinos ML) all
//     reach x* (projected-CG expansion); jacobi must need at most half the
//     iterations of none, amg at most a fifth on D L D and a third on the
//     unscaled Laplacian L (measured 239 / 37 / 669 and 22 / 178):
//     bounds that fail if the preconditioner is not applied.
//     amg-full (a full ML setup per active set) the same bounds; the
//     counters of FreeSetAMG (one aggregation, then recomputes).
//     amg-T8-rel / jacobi-rel: Proportioning step = preconditioned (the
//     projected PCG step on F u R); reaches x*, counts its releases, needs
//     fewer iterations than amg-T8 on L (15 against 22).
//  2a. The membrane of B4 at h = 100: Projected-CG gradient factor 1.25
//     needs at most half the proportioning steps (2 against 8), with the
//     release at most 3/4 of the iterations (14 against 22); the release
//     fewer CG steps.
//  2b. FreeSetAMG's in-place recompute (ML ReComputePreconditioner on
//     A's aggregates) gives the operator of a direct build for that set,
//     not the previous set's; keep_fraction and reset().
//  3. Same solution as unpreconditioned MPRGP on that problem; bad
//     input: amg without a factory, jacobi without a diagonal; a
//     negative definite M_F (the safeguard falls back to phi).
#include "planted_problems.h"

#include <qp/free_set_amg.h>
#include <qp/membrane_generator.h>
#include <qp/solver_factory.h>

#include <deal.II/base/mpi.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <iomanip>
#include <map>

using namespace qptest;
using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

namespace
{
  // The exact inverse of A_FF for a dense A: Cholesky of the free block;
  // the active entries of the result are zero.
  Problem<Vec>::FreeSetPreconditioner
  exact_free_set_inverse(const Dense &A, const Vec &mask)
  {
    std::vector<unsigned int> free;
    for (unsigned int i = 0; i < A.n; ++i)
      if (mask[i] == 0.)
        free.push_back(i);
    const unsigned int  m = free.size();
    std::vector<double> L(m * m, 0.);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j <= i; ++j)
      {
        double s = A.a[free[i] * A.n + free[j]];
        for (unsigned int k = 0; k < j; ++k)
          s -= L[i * m + k] * L[j * m + k];
        if (i == j)
        {
          AssertThrow(s > 0., dealii::ExcMessage("A_FF not SPD"));
          L[i * m + i] = std::sqrt(s);
        }
        else
          L[i * m + j] = s / L[j * m + j];
      }
    return [L, free, m](Vec &dst, const Vec &src)
    {
      std::vector<double> y(m);
      for (unsigned int i = 0; i < m; ++i)
      {
        double s = src[free[i]];
        for (unsigned int k = 0; k < i; ++k)
          s -= L[i * m + k] * y[k];
        y[i] = s / L[i * m + i];
      }
      for (unsigned int i = m; i-- > 0;)
      {
        double s = y[i];
        for (unsigned int k = i + 1; k < m; ++k)
          s -= L[k * m + i] * y[k];
        y[i] = s / L[i * m + i];
      }
      dst = 0.;
      for (unsigned int i = 0; i < m; ++i)
        dst[free[i]] = y[i];
    };
  }

  // 5-point Laplacian on an m x m grid (Dirichlet), scaled D L D with
  // D_ii = scale_i
  void
  scaled_laplacian(const unsigned int            m,
                   const std::vector<double>    &scale,
                   dealii::SparsityPattern      &sp,
                   dealii::SparseMatrix<double> &A)
  {
    const unsigned int n = m * m;
    sp.reinit(n, n, 5);
    const auto for_each = [&](auto &&f)
    {
      for (unsigned int r = 0; r < m; ++r)
        for (unsigned int c = 0; c < m; ++c)
        {
          const unsigned int i = r * m + c;
          f(i, i, 4.);
          if (r > 0)
            f(i, i - m, -1.);
          if (r + 1 < m)
            f(i, i + m, -1.);
          if (c > 0)
            f(i, i - 1, -1.);
          if (c + 1 < m)
            f(i, i + 1, -1.);
        }
    };
    for_each([&](unsigned int i, unsigned int j, double) { sp.add(i, j); });
    sp.compress();
    A.reinit(sp);
    for_each([&](unsigned int i, unsigned int j, double v)
             { A.set(i, j, scale[i] * v * scale[j]); });
  }

  struct SparsePlanted
  {
    dealii::SparsityPattern      sp;
    dealii::SparseMatrix<double> A;
    Vec                          x_star, b, lower;
    unsigned int                 n_active = 0;
  };

  // bounds x >= l on every unknown; active (x* = l, multiplier in [0.5,
  // 1.5]) in the block of grid columns c < 0.4 m, rows 0.2 m <= r < 0.8 m
  // (a contact zone), strictly above l elsewhere
  void
  make_sparse_planted(const unsigned int         m,
                      const std::vector<double> &scale,
                      SparsePlanted             &P)
  {
    std::mt19937 rng(17);
    scaled_laplacian(m, scale, P.sp, P.A);
    const unsigned int n = m * m;
    P.x_star.reinit(n);
    P.lower.reinit(n);
    Vec mu(n);
    for (unsigned int r = 0; r < m; ++r)
      for (unsigned int c = 0; c < m; ++c)
      {
        const unsigned int i = r * m + c;
        P.lower[i]           = uniform(rng, -1., -0.5);
        const bool active    = c < 0.4 * m && r >= 0.2 * m && r < 0.8 * m;
        if (active)
        {
          P.x_star[i] = P.lower[i];
          mu[i]       = uniform(rng, 0.5, 1.5);
          ++P.n_active;
        }
        else
          P.x_star[i] = P.lower[i] + uniform(rng, 0.1, 1.);
      }
    P.b.reinit(n);
    P.A.vmult(P.b, P.x_star);
    P.b -= mu; // b = A x* - mu, i.e. g(x*) = mu >= 0 on the active set
  }

  Problem<Vec>
  sparse_problem(const SparsePlanted &P)
  {
    Problem<Vec> problem;
    problem.hessian = [&P](Vec &dst, const Vec &src) { P.A.vmult(dst, src); };
    problem.b       = P.b;
    auto diagonal   = std::make_shared<Vec>(P.b.size());
    for (unsigned int i = 0; i < P.b.size(); ++i)
      (*diagonal)[i] = P.A.diag_element(i);
    problem.diagonal = diagonal;
    auto set         = std::make_shared<SeparableSet<Vec>>();
    for (unsigned int i = 0; i < P.b.size(); ++i)
      set->add_bound(i, P.lower[i]);
    set->finalize(P.b);
    problem.constraints = set;
    return problem;
  }

  bool
  kkt_ok(const SolverStatistics &s)
  {
    return s.kkt.stationarity <= 1e-9 * s.norm_b &&
           s.kkt.feasibility <= 1e-12 &&
           s.kkt.complementarity <= 1e-8 * s.norm_b;
  }

  std::string
  kkt_text(const SolverStatistics &s)
  {
    return "KKT " + sci(s.kkt.stationarity) + " " + sci(s.kkt.feasibility) +
           " " + sci(s.kkt.complementarity);
  }
} // namespace


int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checker                                 &check = checker();

  // ---- 1. planted dense problems
  std::cout << "planted dense QPs (kappa 1e3), tolerance 1e-10" << std::endl;
  std::cout << std::setw(12) << "M" << std::setw(10) << "set" << std::setw(6)
            << "seed" << std::setw(7) << "iter" << std::setw(6) << "cg"
            << std::setw(6) << "half" << std::setw(6) << "prop" << std::setw(8)
            << "setups" << std::setw(11) << "|x-x*|" << std::endl;
  const std::vector<std::pair<std::string, std::vector<BlockType>>> sets = {
    {"bound", {BlockType::bound}},
    {"box", {BlockType::box}},
    {"bound+box", {BlockType::bound, BlockType::box}}};
  for (const std::string M : {"none", "jacobi", "exact"})
    for (const auto &set_case : sets)
      for (const unsigned int seed : {1u, 2u, 3u})
      {
        const Planted P =
          make_planted(set_case.second, 40, 8, 100 * seed + 11, 1e3);
        const unsigned int n = P.x_star.size();
        Vec                layout(n);
        auto               problem  = make_problem(P.A, P.b, P.blocks, layout);
        auto               diagonal = std::make_shared<Vec>(n);
        for (unsigned int i = 0; i < n; ++i)
          (*diagonal)[i] = P.A.a[i * n + i];
        problem.diagonal = diagonal;
        SolverParameters prm;
        prm.tolerance                = 1e-10;
        prm.max_iterations           = 5000;
        prm.preconditioner           = M == "exact" ? "amg" : M;
        unsigned int n_factory_calls = 0;
        if (M == "exact")
          problem.free_set_preconditioner = [&](const Vec &mask)
          {
            ++n_factory_calls;
            return exact_free_set_inverse(P.A, mask);
          };
        auto         qp = create<Vec>("mprgp", prm);
        Vec          x(n);
        const auto   stats = qp->solve(problem, x);
        const double err   = distance(x, P.x_star);
        std::cout << std::setw(10) << M << std::setw(10) << set_case.first
                  << std::setw(6) << seed << std::setw(7) << stats.iterations
                  << std::setw(6) << stats.n_cg << std::setw(6)
                  << stats.n_half_steps << std::setw(6) << stats.n_proportioning
                  << std::setw(8) << stats.n_preconditioner_setups
                  << std::setw(11) << sci(err) << "  "
                  << to_string(stats.reason) << std::endl;
        const std::string tag =
          M + "/" + set_case.first + "/" + std::to_string(seed) + ": ";
        check.verbose = false;
        check.check(stats.converged(),
                    tag + "converged (" + to_string(stats.reason) + ")");
        check.check(err <= 1e-8 * (1. + norm(P.x_star)),
                    tag + "||x - x*|| = " + sci(err));
        check.check(kkt_ok(stats), tag + kkt_text(stats));
        if (M == "none")
          check.check(stats.n_preconditioner_setups == 0 &&
                        stats.n_preconditioner_applications == 0,
                      tag + "no preconditioner used");
        else
          check.check(stats.n_preconditioner_setups >= 1 &&
                        stats.n_preconditioner_applications >= stats.n_cg,
                      tag + "preconditioner built and applied (" +
                        std::to_string(stats.n_preconditioner_setups) +
                        " setups, " +
                        std::to_string(stats.n_preconditioner_applications) +
                        " applications)");
        if (M == "exact")
        {
          check.check(n_factory_calls == stats.n_preconditioner_setups,
                      tag + "factory called once per setup");
          // with the exact inverse of A_FF the first CG step on a face
          // reaches the face's minimizer: every CG step but the first
          // of each face (a restart) is a correction of rounding only,
          // so the CG steps are at most the restarts plus a few
          const unsigned int restarts =
            1 + stats.n_half_steps + stats.n_proportioning;
          check.check(stats.n_cg <= 2 * restarts + 2,
                      tag + std::to_string(stats.n_cg) + " CG steps for " +
                        std::to_string(restarts) + " faces (exact M_F)");
        }
      }
  check.verbose = true;

  // ---- 2. planted sparse QP, badly scaled 5-point Laplacian
  const unsigned int  m = 60, n = m * m;
  std::vector<double> scale(n), unit(n, 1.);
  {
    std::mt19937 rng(5);
    for (double &s : scale)
      s = std::pow(10., uniform(rng, 0., 1.));
  }
  std::cout << "\nplanted sparse QP, 5-point Laplacian " << m << " x " << m
            << ", tolerance 1e-10" << std::endl;
  std::cout << std::setw(8) << "A" << std::setw(12) << "M" << std::setw(7)
            << "iter" << std::setw(6) << "cg" << std::setw(6) << "half"
            << std::setw(6) << "prop" << std::setw(8) << "setups"
            << std::setw(11) << "|x-x*|" << std::endl;
  std::map<std::string, unsigned int> iterations;
  for (const std::string matrix : {"DLD", "L"})
  {
    SparsePlanted P;
    make_sparse_planted(m, matrix == "DLD" ? scale : unit, P);
    Vec x_plain;
    for (const std::string M : {"none",
                                "jacobi",
                                "amg",
                                "amg-full",
                                "amg-T8",
                                "amg-T8-rel",
                                "amg-T8-rel-G",
                                "jacobi-rel"})
    {
      Problem<Vec>                problem = sparse_problem(P);
      std::unique_ptr<FreeSetAMG> amg;
      if (M != "none" && M != "jacobi" && M != "jacobi-rel")
      {
        // amg-full: a full ML setup (new aggregates) for every active set
        FreeSetAMG::Parameters amg_prm;
        amg_prm.reuse_aggregates = M != "amg-full";
        amg                      = std::make_unique<FreeSetAMG>(P.A, amg_prm);
        problem.free_set_preconditioner = amg->factory();
      }
      SolverParameters prm;
      prm.tolerance      = 1e-10;
      prm.max_iterations = 20000;
      prm.preconditioner = (M == "jacobi" || M == "jacobi-rel") ? "jacobi" :
                           M == "none"                          ? "none" :
                                                                  "amg";
      // amg-T8: eight step lengths in the projected-CG expansion
      if (M == "amg-T8" || M == "amg-T8-rel" || M == "amg-T8-rel-G")
        prm.projected_cg_trials = 8;
      // -G: the least-cost trial among those within 1.25 of the least
      // ||g^P||
      if (M == "amg-T8-rel-G")
        prm.projected_cg_gradient_factor = 1.25;
      // -rel: the preconditioned release as the proportioning step
      if (M == "amg-T8-rel" || M == "amg-T8-rel-G" || M == "jacobi-rel")
        prm.proportioning_step = "preconditioned";
      // the projected-CG expansion: with the alpha-bar one a
      // preconditioned direction hits a bound at every step and the active
      // set grows by a few unknowns per expansion (doc/benchmarks/
      // membrane.md)
      prm.expansion = "projected-cg";
      auto       qp = create<Vec>("mprgp", prm);
      Vec        x(n);
      const auto stats = qp->solve(problem, x);
      Vec        diff(x);
      diff -= P.x_star;
      const double err = diff.l2_norm();
      std::cout << std::setw(8) << matrix << std::setw(12) << M << std::setw(7)
                << stats.iterations << std::setw(6) << stats.n_cg
                << std::setw(6) << stats.n_half_steps << std::setw(6)
                << stats.n_proportioning << std::setw(8)
                << stats.n_preconditioner_setups << std::setw(11) << sci(err)
                << "  " << to_string(stats.reason) << std::endl;
      const std::string tag        = matrix + "/" + M + ": ";
      iterations[matrix + "/" + M] = stats.iterations;
      check.check(stats.converged(),
                  tag + "converged (" + to_string(stats.reason) + ")");
      check.check(err <= 1e-8 * (1. + P.x_star.l2_norm()),
                  tag + "||x - x*|| = " + sci(err));
      check.check(kkt_ok(stats), tag + kkt_text(stats));
      if (M == "none")
        x_plain = x;
      else
      {
        diff = x;
        diff -= x_plain;
        check.check(diff.l2_norm() <= 1e-8 * (1. + x_plain.l2_norm()),
                    tag + "same solution as unpreconditioned MPRGP (" +
                      sci(diff.l2_norm()) + ")");
      }
      if (M == "amg-T8-rel" || M == "amg-T8-rel-G" || M == "jacobi-rel")
        check.check(stats.n_preconditioned_releases >= 1 &&
                      stats.n_preconditioned_releases <= stats.n_proportioning,
                    tag + std::to_string(stats.n_preconditioned_releases) +
                      " of " + std::to_string(stats.n_proportioning) +
                      " proportioning steps as preconditioned releases");
      else
        check.check(stats.n_preconditioned_releases == 0,
                    tag + "no preconditioned release by default");
      if (M != "none" && M != "jacobi" && M != "jacobi-rel")
      {
        // every factory call is a setup, a recompute, or (keep_fraction,
        // 0 here) a kept hierarchy; with reused aggregates exactly one
        // aggregation (of A itself, the first build at x0 = 0 where every
        // unknown is free: no recompute there)
        check.check(
          amg->n_kept() == 0 &&
            (M == "amg-full" ?
               amg->n_full_setups() == stats.n_preconditioner_setups &&
                 amg->n_recomputes() == 0 :
               amg->n_full_setups() == 1 &&
                 amg->n_recomputes() + 1 == stats.n_preconditioner_setups),
          tag + std::to_string(amg->n_full_setups()) + " full ML setups, " +
            std::to_string(amg->n_recomputes()) + " recomputes");
      }
      if (M != "none" && M != "jacobi" && M != "jacobi-rel")
        check.check(stats.n_preconditioner_setups >= 1 &&
                      stats.n_preconditioner_setups <=
                        1 + stats.n_half_steps + stats.n_proportioning,
                    tag + std::to_string(stats.n_preconditioner_setups) +
                      " AMG setups, at most one per active set");
    }
  }
  // the preconditioners do their job (bounds with a margin over the
  // measured counts, far below the unpreconditioned ones)
  check.check(iterations["DLD/jacobi"] * 2 <= iterations["DLD/none"],
              "D L D: jacobi " + std::to_string(iterations["DLD/jacobi"]) +
                " iterations, at most half of none's " +
                std::to_string(iterations["DLD/none"]));
  check.check(iterations["DLD/amg"] * 5 <= iterations["DLD/none"],
              "D L D: amg " + std::to_string(iterations["DLD/amg"]) +
                " iterations, at most a fifth of none's " +
                std::to_string(iterations["DLD/none"]));
  check.check(iterations["DLD/amg-T8"] * 5 <= iterations["DLD/none"] &&
                iterations["L/amg-T8"] * 3 <= iterations["L/none"],
              "amg with 8 projected-CG trials: " +
                std::to_string(iterations["DLD/amg-T8"]) + " (D L D) and " +
                std::to_string(iterations["L/amg-T8"]) +
                " (L) iterations, at most a fifth / a third of none's");
  check.check(iterations["L/amg"] * 3 <= iterations["L/none"],
              "L: amg " + std::to_string(iterations["L/amg"]) +
                " iterations, at most a third of none's " +
                std::to_string(iterations["L/none"]));
  check.check(iterations["DLD/amg-full"] * 5 <= iterations["DLD/none"] &&
                iterations["L/amg-full"] * 3 <= iterations["L/none"],
              "amg with a full setup per active set: " +
                std::to_string(iterations["DLD/amg-full"]) + " (D L D) and " +
                std::to_string(iterations["L/amg-full"]) +
                " (L) iterations, at most a fifth / a third of none's");

  // the preconditioned release does the first PCG step on the enlarged
  // face: fewer iterations on L, whose contact zone is released over 7
  // proportioning steps (measured 15 against 22)
  check.check(iterations["L/amg-T8-rel"] < iterations["L/amg-T8"] &&
                iterations["DLD/amg-T8-rel"] <= iterations["DLD/amg-T8"],
              "preconditioned release: " +
                std::to_string(iterations["L/amg-T8-rel"]) + " (L) and " +
                std::to_string(iterations["DLD/amg-T8-rel"]) +
                " (D L D) iterations against amg-T8's " +
                std::to_string(iterations["L/amg-T8"]) + " and " +
                std::to_string(iterations["DLD/amg-T8"]));

  // ---- 2a. the membrane of benchmark B4 at h = 100 (n = 10^4), tolerance
  // 1e-6: amg with 8 projected-CG trials releases the over-activated
  // contact zone one grid line per proportioning step (8 steps, 22
  // iterations); the gradient factor 1.25 avoids the over-activation (2
  // proportioning steps, 15 iterations; 14 with the preconditioned
  // release); the preconditioned release alone saves CG steps (6 against
  // 12, 16 iterations).  Measured counts; the bounds fail if the options
  // do nothing.
  {
    MembraneGenerator::Parameters mprm;
    mprm.h                      = 100;
    const auto         membrane = MembraneGenerator(mprm).generate();
    const unsigned int nm       = membrane->size();
    std::map<std::string, SolverStatistics> runs;
    for (const std::string M : {"T8", "T8-rel", "T8-G", "T8-rel-G"})
    {
      Problem<Vec> problem;
      problem.hessian = [&membrane](Vec &dst, const Vec &src)
      { membrane->hessian.vmult(dst, src); };
      problem.b = membrane->rhs;
      auto set  = std::make_shared<SeparableSet<Vec>>();
      for (unsigned int i = 0; i < nm; ++i)
        set->add_bound(i, membrane->constraints[0].lower[i]);
      set->finalize(problem.b);
      problem.constraints = set;
      FreeSetAMG amg(membrane->hessian);
      problem.free_set_preconditioner = amg.factory();
      SolverParameters prm;
      prm.tolerance           = 1e-6;
      prm.gamma               = 2.;
      prm.expansion           = "projected-cg";
      prm.projected_cg_trials = 8;
      prm.preconditioner      = "amg";
      if (M.find("rel") != std::string::npos)
        prm.proportioning_step = "preconditioned";
      if (M.find("G") != std::string::npos)
        prm.projected_cg_gradient_factor = 1.25;
      Vec        x(nm);
      const auto stats = create<Vec>("mprgp", prm)->solve(problem, x);
      runs[M]          = stats;
      std::cout << "membrane h = 100 " << std::setw(9) << M << ": "
                << stats.iterations << " iterations (" << stats.n_cg << " CG, "
                << stats.n_half_steps << " half, " << stats.n_proportioning
                << " proportioning), " << to_string(stats.reason) << std::endl;
      check.check(stats.converged() &&
                    stats.kkt.stationarity <= 1e-6 * stats.norm_b &&
                    stats.kkt.feasibility <= 1e-12,
                  "membrane " + M + ": converged, " + kkt_text(stats));
    }
    check.check(
      runs["T8-G"].n_proportioning * 2 <= runs["T8"].n_proportioning &&
        runs["T8-rel-G"].iterations * 4 <= runs["T8"].iterations * 3,
      "membrane: gradient factor 1.25: " +
        std::to_string(runs["T8-G"].n_proportioning) +
        " proportioning steps against " +
        std::to_string(runs["T8"].n_proportioning) + "; with the release " +
        std::to_string(runs["T8-rel-G"].iterations) + " iterations against " +
        std::to_string(runs["T8"].iterations));
    check.check(runs["T8-rel"].n_cg < runs["T8"].n_cg &&
                  runs["T8-rel"].n_preconditioned_releases >= 1,
                "membrane: the preconditioned release: " +
                  std::to_string(runs["T8-rel"].n_cg) + " CG steps against " +
                  std::to_string(runs["T8"].n_cg));
  }

  // ---- 2b. FreeSetAMG's in-place recompute sees the new entries: a
  // hierarchy recomputed for set B after set A applies the same operator
  // as one built for B directly (both on A's aggregates), and another one
  // than for set A (a stale copy of the matrix inside ML would give A's)
  {
    SparsePlanted P;
    make_sparse_planted(30, std::vector<double>(900, 1.), P);
    Vec mask_a(900), mask_b(900), r(900), y_ab(900), y_b(900), y_a(900);
    std::mt19937 rng(3);
    for (unsigned int i = 0; i < 900; ++i)
    {
      const unsigned int row = i / 30, col = i % 30;
      mask_a[i] = col < 10 && row >= 6 && row < 24;
      mask_b[i] = col < 12 && row >= 4 && row < 26;
      r[i]      = uniform(rng, -1., 1.);
    }
    FreeSetAMG first(P.A), second(P.A);
    first.build(mask_a)(y_a, r);
    first.build(mask_b)(y_ab, r);
    second.build(mask_b)(y_b, r);
    Vec diff(y_ab);
    diff -= y_b;
    check.check(diff.l2_norm() <= 1e-12 * y_b.l2_norm(),
                "recompute for set B after set A = built for B: " +
                  sci(diff.l2_norm() / y_b.l2_norm()));
    diff = y_ab;
    diff -= y_a;
    check.check(diff.l2_norm() >= 1e-3 * y_b.l2_norm(),
                "the recomputed operator differs from set A's: " +
                  sci(diff.l2_norm() / y_b.l2_norm()));
    check.check(first.n_full_setups() == 1 && first.n_recomputes() == 2 &&
                  second.n_full_setups() == 1 && second.n_recomputes() == 1,
                "one aggregation each, the rest recomputes");
    // keep_fraction: a set that differs in at most that fraction keeps
    // the hierarchy (mask B differs from A in 84 of 900 unknowns)
    FreeSetAMG::Parameters keep;
    keep.keep_fraction = 0.2;
    FreeSetAMG third(P.A, keep);
    third.build(mask_a);
    third.build(mask_b)(y_b, r);
    diff = y_b;
    diff -= y_a;
    check.check(third.n_kept() == 1 && diff.l2_norm() <= 1e-14 * y_a.l2_norm(),
                "keep fraction 0.2: set B keeps set A's hierarchy");
    third.reset();
    third.build(mask_b);
    check.check(third.n_full_setups() == 2 && third.n_kept() == 1,
                "after reset() a full setup");
  }

  // ---- 3. bad input
  {
    SparsePlanted P;
    make_sparse_planted(10, std::vector<double>(100, 1.), P);
    for (const std::string M : {"amg", "jacobi"})
    {
      Problem<Vec> problem = sparse_problem(P);
      if (M == "jacobi")
        problem.diagonal.reset();
      SolverParameters prm;
      prm.preconditioner = M;
      auto        qp     = create<Vec>("mprgp", prm);
      Vec         x(100);
      std::string message;
      try
      {
        qp->solve(problem, x);
      }
      catch (const std::exception &e)
      {
        message = e.what();
      }
      check.check(message.find(M == "amg" ?
                                 "free_set_preconditioner" :
                                 "Problem::diagonal") != std::string::npos,
                  "Preconditioner = " + M +
                    " without what it needs is refused with a message "
                    "naming it");
    }
  }
  // a gradient factor in (0, 1)
  {
    SolverParameters prm;
    prm.projected_cg_gradient_factor = 0.5;
    std::string message;
    try
    {
      prm.check();
    }
    catch (const std::exception &e)
    {
      message = e.what();
    }
    check.check(message.find("Projected-CG gradient factor") !=
                  std::string::npos,
                "Projected-CG gradient factor 0.5 is refused, naming it");
  }
  // the preconditioned release without a preconditioner
  {
    SolverParameters prm;
    prm.proportioning_step = "preconditioned";
    std::string message;
    try
    {
      prm.check();
    }
    catch (const std::exception &e)
    {
      message = e.what();
    }
    check.check(message.find("Proportioning step") != std::string::npos &&
                  message.find("Preconditioner") != std::string::npos,
                "Proportioning step = preconditioned with Preconditioner = "
                "none is refused, naming both parameters");
  }
  // a factory whose operator is negative definite (dst = -src): the
  // safeguard falls back to phi, and the solve still reaches x*
  {
    SparsePlanted P;
    make_sparse_planted(20, std::vector<double>(400, 1.), P);
    Problem<Vec> problem            = sparse_problem(P);
    problem.free_set_preconditioner = [](const Vec &)
    {
      return Problem<Vec>::FreeSetPreconditioner(
        [](Vec &dst, const Vec &src)
        {
          dst = src;
          dst *= -1.;
        });
    };
    SolverParameters prm;
    prm.tolerance      = 1e-10;
    prm.preconditioner = "amg";
    auto       qp      = create<Vec>("mprgp", prm);
    Vec        x(400);
    const auto stats = qp->solve(problem, x);
    Vec        diff(x);
    diff -= P.x_star;
    check.check(stats.converged() &&
                  diff.l2_norm() <= 1e-8 * (1. + P.x_star.l2_norm()) &&
                  kkt_ok(stats),
                "negative definite M_F: safeguard, converged to x* (" +
                  sci(diff.l2_norm()) + ", " + to_string(stats.reason) + ")");
  }
  return check.finish("mprgp_preconditioned");
}
