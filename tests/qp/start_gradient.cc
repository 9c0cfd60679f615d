// Loops of QPs with the same A and b, where only the set changes (the
// Coulomb fixed point over Tresca QPs of lib/fclib/local_solver.cc):
//  - SolverBase::final_gradient(): after a converged MPGP / MPGP-BB solve it
//    is A x - b at the returned x (against a fresh product, 1e-12);
//  - Problem::start_gradient: the same QP again from that x and gradient is
//    converged with no product at all;
//  - smaller radii for every sixth disc (SeparableSet::set_disc_radius), so
//  that
//    the projection moves a few blocks of the start (moves by rounding,
//    from projecting a point on a disc's rim again, are no moves): with
//    Problem::hessian_add_sparse (columns of A) the solve takes one product
//    fewer than the same solve without the start gradient, and both reach
//    the solution of a solve from scratch on a newly built set (1e-9) with
//    KKT residuals recomputed here below the tolerance;
//  - without hessian_add_sparse, a moved start costs the product again;
//  - set_disc_radius / set_box_bounds: projections bitwise equal to those of
//    a newly built set, and bad values refused;
//  - SolverBase::set_tolerance: one solver object solves to 1e-2, then to
//    1e-10; a non-positive tolerance is refused.
#include "planted_problems.h"

#include <qp/kkt_residuals.h>
#include <qp/solver_factory.h>

using namespace qptest;
using namespace dualcontact::qp;
using Vec = dealii::Vector<double>;

namespace
{
  constexpr unsigned int n_discs = 30, n_boxes = 10;
  constexpr unsigned int n = 2 * n_discs + n_boxes;

  std::shared_ptr<SeparableSet<Vec>>
  make_disc_set(const std::vector<double> &radius,
                const std::vector<double> &box_bound,
                const Vec                 &layout)
  {
    auto set = std::make_shared<SeparableSet<Vec>>();
    for (unsigned int k = 0; k < n_discs; ++k)
      set->add_disc(2 * k, radius[k]);
    for (unsigned int k = 0; k < n_boxes; ++k)
      set->add_box(2 * n_discs + k, -box_bound[k], box_bound[k]);
    set->finalize(layout);
    return set;
  }

  double
  distance(const Vec &x, const Vec &y)
  {
    Vec d(x);
    d -= y;
    return d.l2_norm();
  }

  double
  gradient_error(const Dense &A, const Vec &b, const Vec &x, const Vec &g)
  {
    std::vector<double> y(n);
    A.vmult(y.data(), x.begin());
    double e = 0., s = 0.;
    for (unsigned int i = 0; i < n; ++i)
    {
      e = std::max(e, std::abs(y[i] - b[i] - g[i]));
      s = std::max(s, std::abs(y[i] - b[i]));
    }
    return e / s;
  }
} // namespace

int
main()
{
  Checker      check;
  std::mt19937 rng(7);
  const Dense  A = random_spd(n, 1., 100., rng);
  Vec          layout(n);
  Problem<Vec> problem;
  problem.b.reinit(n);
  for (unsigned int i = 0; i < n; ++i)
    problem.b[i] = uniform(rng, -20., 20.);
  problem.lambda_max = 101.; // spectrum in [1, 100]: no power iteration
  auto Ap            = std::make_shared<Dense>(A);
  problem.hessian    = [Ap](Vec &dst, const Vec &src)
  { Ap->vmult(dst.begin(), src.begin()); };
  const auto columns =
    [Ap](Vec &dst, const Vec &d, const std::vector<std::size_t> &indices)
  {
    for (unsigned int i = 0; i < n; ++i)
      for (const std::size_t j : indices)
        dst[i] += Ap->a[i * n + j] * d[j];
  };
  std::vector<double> radius(n_discs), box_bound(n_boxes);
  for (double &r : radius)
    r = uniform(rng, 0.2, 1.);
  for (double &r : box_bound)
    r = uniform(rng, 0.2, 1.);
  const double tol = 1e-10;

  for (const std::string solver_name : {"mpgp", "mpgp-bb"})
  {
    SolverParameters prm;
    prm.tolerance       = tol;
    auto solver         = create<Vec>(solver_name, prm);
    auto set            = make_disc_set(radius, box_bound, layout);
    problem.constraints = set;
    problem.start_gradient.reset();
    problem.hessian_add_sparse = nullptr;
    Vec        x(n);
    const auto s1 = solver->solve(problem, x);
    const Vec *g1 = solver->final_gradient();
    check.check(s1.converged() && g1 != nullptr &&
                  gradient_error(A, problem.b, x, *g1) < 1e-12,
                solver_name + ": QP 1 converged (" +
                  std::to_string(s1.iterations) +
                  " iterations) and final_gradient() = A x - b");
    if (g1 == nullptr)
      continue;
    const auto gradient = std::make_shared<Vec>(*g1);

    // the same QP from its solution and gradient: no product
    {
      Vec x_again(x);
      problem.start_gradient = gradient;
      const auto s           = solver->solve(problem, x_again);
      check.check(s.converged() && s.iterations == 0 &&
                    s.n_hessian_products == 0 &&
                    distance(x_again, x) <= 1e-14 * x.l2_norm(),
                  solver_name + ": the same QP again from its gradient: " +
                    std::to_string(s.n_hessian_products) + " products");
    }

    // smaller radii on every sixth disc: the start is cut there
    std::vector<double> radius2 = radius;
    for (unsigned int k = 0; k < n_discs; k += 6)
      radius2[k] *= 0.5;
    Vec x_scratch(x);
    {
      problem.constraints = make_disc_set(radius2, box_bound, layout);
      problem.start_gradient.reset();
      const auto s = create<Vec>(solver_name, prm)->solve(problem, x_scratch);
      check.check(s.converged(), solver_name + ": QP 2 on a new set converged");
    }
    for (unsigned int k = 0; k < n_discs; ++k)
      set->set_disc_radius(k, radius2[k]);
    problem.constraints         = set;
    unsigned int plain_products = 0;
    {
      Vec x_plain(x);
      problem.start_gradient.reset();
      const auto s   = solver->solve(problem, x_plain);
      plain_products = s.n_hessian_products;
      check.check(s.converged() && distance(x_plain, x_scratch) < 1e-9,
                  solver_name + ": QP 2 on the updated set, no start "
                                "gradient: the new set's solution");
    }
    {
      Vec x_given(x);
      problem.start_gradient     = gradient;
      problem.hessian_add_sparse = columns;
      const auto   s             = solver->solve(problem, x_given);
      const auto   kkt           = compute_kkt_residuals(problem, x_given);
      const double norm_b        = problem.b.l2_norm();
      check.check(s.converged() && distance(x_given, x_scratch) < 1e-9 &&
                    kkt.stationarity <= 10 * tol * norm_b &&
                    kkt.feasibility <= 1e-12,
                  solver_name +
                    ": QP 2 from the corrected start gradient: "
                    "the same solution, KKT stationarity " +
                    sci(kkt.stationarity / norm_b));
      check.check(s.n_hessian_products + 1 == plain_products,
                  solver_name + ": one product fewer (" +
                    std::to_string(s.n_hessian_products) + " vs " +
                    std::to_string(plain_products) + ")");
      const Vec *g2 = solver->final_gradient();
      check.check(g2 != nullptr &&
                    gradient_error(A, problem.b, x_given, *g2) < 1e-12,
                  solver_name + ": final_gradient() after QP 2 = A x - b");
    }
    {
      // without the column operator a moved start costs the product
      Vec x_given(x);
      problem.start_gradient     = gradient;
      problem.hessian_add_sparse = nullptr;
      const auto s               = solver->solve(problem, x_given);
      check.check(s.converged() && s.n_hessian_products == plain_products,
                  solver_name + ": moved start without hessian_add_sparse: " +
                    std::to_string(s.n_hessian_products) + " products");
    }
    for (unsigned int k = 0; k < n_discs; ++k)
      set->set_disc_radius(k, radius[k]);
  }

  // set_disc_radius / set_box_bounds against a newly built set
  {
    auto                set = make_disc_set(radius, box_bound, layout);
    std::vector<double> radius2(n_discs), box2(n_boxes);
    for (double &r : radius2)
      r = uniform(rng, 0., 1.);
    radius2[3] = 0.;
    for (double &r : box2)
      r = uniform(rng, 0., 1.);
    for (unsigned int k = 0; k < n_discs; ++k)
      set->set_disc_radius(k, radius2[k]);
    for (unsigned int k = 0; k < n_boxes; ++k)
      set->set_box_bounds(k, -box2[k], box2[k]);
    const auto fresh = make_disc_set(radius2, box2, layout);
    bool       equal = true;
    for (unsigned int trial = 0; trial < 20; ++trial)
    {
      Vec y(n);
      for (unsigned int i = 0; i < n; ++i)
        y[i] = uniform(rng, -2., 2.);
      Vec z(y);
      set->project(y);
      fresh->project(z);
      equal = equal && y == z;
    }
    check.check(equal,
                "updated radii and box bounds: projections bitwise "
                "equal to a new set's");
    bool refused = false;
    try
    {
      set->set_disc_radius(0, -1.);
    }
    catch (const dealii::ExceptionBase &)
    {
      refused = true;
    }
    bool refused_box = false;
    try
    {
      set->set_box_bounds(0, 1., -1.);
    }
    catch (const dealii::ExceptionBase &)
    {
      refused_box = true;
    }
    bool refused_index = false;
    try
    {
      set->set_disc_radius(n_discs, 1.);
    }
    catch (const dealii::ExceptionBase &)
    {
      refused_index = true;
    }
    check.check(refused && refused_box && refused_index,
                "negative radius, lower > upper and a disc index out of "
                "range are refused");
  }

  // set_tolerance
  {
    SolverParameters prm;
    prm.tolerance       = 1e-2;
    auto solver         = create<Vec>("mpgp-bb", prm);
    problem.constraints = make_disc_set(radius, box_bound, layout);
    problem.start_gradient.reset();
    problem.hessian_add_sparse = nullptr;
    Vec        x(n);
    const auto loose = solver->solve(problem, x);
    solver->set_tolerance(1e-10, 1000);
    x                 = 0.;
    const auto strict = solver->solve(problem, x);
    check.check(loose.converged() && strict.converged() &&
                  loose.final_criterion <= 1e-2 &&
                  loose.final_criterion > 1e-10 &&
                  strict.final_criterion <= 1e-10 &&
                  strict.iterations > loose.iterations &&
                  solver->parameters().tolerance == 1e-10 &&
                  solver->parameters().max_iterations == 1000,
                "set_tolerance: the same solver to 1e-2 (" +
                  sci(loose.final_criterion) + ") then 1e-10 (" +
                  sci(strict.final_criterion) + ")");
    bool refused = false;
    try
    {
      solver->set_tolerance(0., 10);
    }
    catch (const dealii::ExceptionBase &)
    {
      refused = true;
    }
    check.check(refused && solver->parameters().tolerance == 1e-10,
                "set_tolerance(0) is refused and changes nothing");
  }
  return check.finish("start_gradient");
}
