// LocalSolver and the FCLIB error on problems with closed-form solutions:
// one contact with W = diag(k_n, k_t, k_t), sliding and sticking; the cone
// QP (a relaxation: the projection of -q onto the cone for W = I); dense and
// sparse storage of W; contact scaling (two contacts of different
// compliance); the inexact fixed point; the proximal loop on the
// rigid-body files (Capsules: the plain loop fails and says so, auto
// switches the proximal loop on and converges; spheres-in-a-box at 1e-4
// and, through the extrapolated proximal loop, at 1e-8, in at most 80000
// products);
// write and read back a problem with its solution.
#include <fclib/accuracy.h>
#include <fclib/fclib_file.h>
#include <fclib/local_solver.h>
#include <test_tools.h>

#include <cmath>
#include <filesystem>

using namespace dualcontact;
using test_tools::check;
using test_tools::distance;

namespace
{
  fclib::LocalProblem
  one_contact(const double k_n,
              const double k_t,
              const double q_n,
              const double q_t1,
              const double q_t2,
              const double mu)
  {
    fclib::Triplets W(3, 3);
    W.add(0, 0, k_n);
    W.add(1, 1, k_t);
    W.add(2, 2, k_t);
    dealii::Vector<double> q(3);
    q(0) = q_n;
    q(1) = q_t1;
    q(2) = q_t2;
    return fclib::LocalProblem(3, W, q, {mu});
  }

  struct Solved
  {
    fclib::LocalSolver::Result result;
    dealii::Vector<double>     r;
  };

  /** A cold start of LocalSolver on @p problem. */
  Solved
  solve(const fclib::LocalProblem            &problem,
        const qp::SolverParameters           &prm,
        const contact::CoulombParameters     &coulomb,
        const fclib::LocalSolver::Parameters &loop)
  {
    fclib::LocalSolver s(problem, prm, coulomb, loop);
    Solved             out;
    out.r.reinit(problem.size());
    out.result = s.solve(out.r);
    return out;
  }

  fclib::LocalSolver::Parameters
  with_model(const fclib::Model model)
  {
    fclib::LocalSolver::Parameters p;
    p.model = model;
    return p;
  }
} // namespace

int
main()
{
  qp::SolverParameters       prm;
  contact::CoulombParameters coulomb;
  prm.tolerance            = 1e-12;
  coulomb.tolerance        = 1e-12;
  const auto coulomb_model = with_model(fclib::Model::coulomb_fixed_point);

  for (const std::string solver : {"mpgp", "mpgp-bb", "spg-qp", "apgd"})
  {
    prm.solver = solver;
    // sliding: r_n = -q_n / k_n = 2; stick would need |r_t| = |q_t| / k_t
    // = 1 > mu r_n = 0.6, so r_t = -0.6 q_t/|q_t|, u_n = 0, u_t || q_t
    {
      const auto s = solve(one_contact(2., 4., -4., 3., 0., 0.3),
                           prm,
                           coulomb,
                           coulomb_model);
      check(s.result.converged, solver + " slip: converged", s.result.reason);
      check(distance(s.r, {2., -0.6, 0.}) < 1e-9,
            solver + " slip: |r - r*|",
            distance(s.r, {2., -0.6, 0.}));
      check(s.result.fclib_error < 1e-9,
            solver + " slip: FCLIB error",
            s.result.fclib_error);
      check(s.result.coulomb_changes.size() <= 6,
            solver + " slip: Coulomb iterations",
            s.result.coulomb_changes.size());
    }
    // sticking, tangential load at 45 degrees: r = -W^-1 q
    {
      const auto s = solve(one_contact(1., 2., -1., 0.2, 0.2, 0.5),
                           prm,
                           coulomb,
                           coulomb_model);
      check(s.result.converged, solver + " stick: converged", s.result.reason);
      check(distance(s.r, {1., -0.1, -0.1}) < 1e-9,
            solver + " stick: |r - r*|",
            distance(s.r, {1., -0.1, -0.1}));
      check(s.result.fclib_error < 1e-9,
            solver + " stick: FCLIB error",
            s.result.fclib_error);
    }
    // separation: q_n > 0, r = 0
    {
      const auto s = solve(one_contact(1., 1., 0.5, 0.2, -0.1, 0.5),
                           prm,
                           coulomb,
                           coulomb_model);
      check(s.result.converged && s.r.l2_norm() < 1e-12,
            solver + " separation: r = 0",
            s.r.l2_norm());
    }
    // the cone QP with W = I: r = P_K(-q), a relaxation whose FCLIB error
    // is not zero when the contact slides
    {
      const auto   s = solve(one_contact(1., 1., -1., 0.5, 0., 0.3),
                           prm,
                           coulomb,
                           with_model(fclib::Model::cone));
      const double a = (1. + 0.3 * 0.5) / (1. + 0.09);
      check(s.result.converged, solver + " cone: converged", s.result.reason);
      check(distance(s.r, {a, -0.3 * a, 0.}) < 1e-9,
            solver + " cone: r = P_K(-q), |r - r*|",
            distance(s.r, {a, -0.3 * a, 0.}));
      // the Coulomb solution is (1, -0.3, 0): the relaxation differs
      check(s.result.fclib_error > 1e-2,
            solver + " cone: FCLIB error of the relaxation",
            s.result.fclib_error);
      // De Saxce's shift as a fixed point over the cone QPs: exact
      const auto d = solve(one_contact(1., 1., -1., 0.5, 0., 0.3),
                           prm,
                           coulomb,
                           with_model(fclib::Model::desaxce_fixed_point));
      check(d.result.converged && distance(d.r, {1., -0.3, 0.}) < 1e-9,
            solver + " desaxce: r = (1, -0.3, 0), |r - r*|",
            distance(d.r, {1., -0.3, 0.}));
    }
  }

  // mprgp takes mu = 0 (bounds only)
  {
    prm.solver = "mprgp";
    const auto s =
      solve(one_contact(2., 4., -4., 3., 0., 0.), prm, coulomb, coulomb_model);
    check(s.result.converged && distance(s.r, {2., 0., 0.}) < 1e-12,
          "mprgp frictionless: r = (2, 0, 0)",
          distance(s.r, {2., 0., 0.}));
  }

  // the FCLIB error of a wrong r is what the formula says: r = 0 on a
  // closing contact with W = I, q = (-1, 0, 0): u = q, the residual
  // r - P_K(r - u) = -P_K(e_n) = (-1, 0, 0), scale max(1, 0, 1) = 1
  {
    const auto             problem = one_contact(1., 1., -1., 0., 0., 0.5);
    dealii::Vector<double> r(3);
    check(std::abs(fclib::fclib_error(problem, r) - 1.) < 1e-15,
          "FCLIB error of r = 0",
          fclib::fclib_error(problem, r));
  }

  // dense and sparse storage of a non-symmetric W: the same products, W_s =
  // (W + W')/2 and W_a = (W - W')/2 exactly, and the rank of a singular
  // W_s (two contacts sharing one normal: rank 5 of 6)
  {
    fclib::Triplets W(6, 6);
    for (unsigned int i = 0; i < 6; ++i)
      W.add(i, i, 2. + i);
    W.add(0, 3, 1.5);
    W.add(3, 0, 0.5);
    W.add(1, 4, -0.25);
    dealii::Vector<double> q(6), x(6);
    for (unsigned int i = 0; i < 6; ++i)
      x(i) = 1. + 0.3 * i * i;
    const fclib::LocalProblem dense(
      3, W, q, {0.3, 0.3}, "", fclib::Storage::dense);
    const fclib::LocalProblem sparse(
      3, W, q, {0.3, 0.3}, "", fclib::Storage::sparse);
    check(dense.delassus().dense() && !sparse.delassus().dense(),
          "storage as asked",
          dense.delassus().dense());
    dealii::Vector<double> Wx(6), Wsx(6), Wax(6), expected(6);
    for (const fclib::LocalProblem *p : {&dense, &sparse})
    {
      const std::string name = p->delassus().dense() ? "dense" : "sparse";
      p->velocity(Wx, x);
      p->delassus().symmetric_vmult(Wsx, x);
      p->delassus().antisymmetric_vmult(Wax, x);
      double e_W = 0, e_s = 0, e_a = 0;
      for (unsigned int i = 0; i < 6; ++i)
      {
        double w = 0, ws = 0, wa = 0;
        for (unsigned int j = 0; j < 6; ++j)
        {
          const double a = p->W().el(i, j), b = p->W().el(j, i);
          w += a * x(j);
          ws += 0.5 * (a + b) * x(j);
          wa += 0.5 * (a - b) * x(j);
        }
        e_W = std::max(e_W, std::abs(Wx(i) - w));
        e_s = std::max(e_s, std::abs(Wsx(i) - ws));
        e_a = std::max(e_a, std::abs(Wax(i) - wa));
      }
      check(e_W < 1e-14 && e_s < 1e-14 && e_a < 1e-14,
            name + ": W x, W_s x, W_a x",
            std::max({e_W, e_s, e_a}));
    }
    check(std::abs(dense.delassus().asymmetry() - 1. / 7.) < 1e-15,
          "asymmetry max|W - W'| / max|W| = 1/7",
          dense.delassus().asymmetry());
    fclib::Triplets S(6, 6);
    for (unsigned int i = 0; i < 6; ++i)
      for (unsigned int j = 0; j < 6; ++j)
        S.add(i, j, (i % 3 == 0 && j % 3 == 0) ? 1. : (i == j ? 1. : 0.));
    const fclib::LocalProblem singular(3, S, q, {0.3, 0.3});
    check(singular.delassus().numerical_rank(1e-10) == 5,
          "rank of a singular W_s",
          singular.delassus().numerical_rank(1e-10));
  }

  // contact scaling (r_i / s_i, s_i = W_nn,i^-1/2): two uncoupled contacts
  // of compliance 2 and 100, the slip case above and the stick case with W
  // and q times 100; the scaled QPs (disc radius psi_i / s_i) have the same
  // solution: r = (2, -0.6, 0; 1, -0.1, -0.1)
  for (const std::string solver : {"mpgp", "mpgp-bb"})
  {
    fclib::Triplets W(6, 6);
    for (const auto &[i, w] : std::vector<std::pair<unsigned int, double>>{
           {0, 2.}, {1, 4.}, {2, 4.}, {3, 100.}, {4, 200.}, {5, 200.}})
      W.add(i, i, w);
    dealii::Vector<double> q(6);
    q(0)                              = -4.;
    q(1)                              = 3.;
    q(3)                              = -100.;
    q(4)                              = 20.;
    q(5)                              = 20.;
    const fclib::LocalProblem problem = {3, W, q, {0.3, 0.5}};
    qp::SolverParameters      p       = prm;
    p.solver                          = solver;
    for (const bool scaling : {true, false})
    {
      auto loop            = coulomb_model;
      loop.contact_scaling = scaling;
      const auto        s  = solve(problem, p, coulomb, loop);
      const std::string name =
        solver + (scaling ? " scaled" : " unscaled") + " two contacts";
      check(s.result.converged, name + ": converged", s.result.reason);
      check(distance(s.r, {2., -0.6, 0., 1., -0.1, -0.1}) < 1e-9,
            name + ": |r - r*|",
            distance(s.r, {2., -0.6, 0., 1., -0.1, -0.1}));
      check(s.result.fclib_error < 1e-9,
            name + ": FCLIB error",
            s.result.fclib_error);
    }
  }

  // the inexact fixed point reaches the same accuracy as exact QPs
  // (local_problem_test: 48 contacts, mu = 0.7)
  {
    const fclib::LocalProblem problem =
      fclib::read_local(FCLIB_TEST_DATA_DIR "local_problem_test.hdf5");
    qp::SolverParameters tight = prm;
    tight.solver               = "mpgp-bb";
    tight.tolerance            = 1e-9;
    contact::CoulombParameters loop;
    loop.tolerance  = 1e-8;
    auto exact      = coulomb_model;
    exact.inexact   = false;
    exact.proximal  = fclib::Proximal::off;
    auto inexact    = exact;
    inexact.inexact = true;
    const auto e    = solve(problem, tight, loop, exact);
    const auto i    = solve(problem, tight, loop, inexact);
    check(e.result.converged && i.result.converged,
          "local_problem_test: exact and inexact QPs converge",
          i.result.reason);
    check(e.result.fclib_error < 1e-8 && i.result.fclib_error < 1e-8,
          "local_problem_test: FCLIB error of both below 1e-8",
          std::max(e.result.fclib_error, i.result.fclib_error));
    bool non_increasing = true;
    for (unsigned int k = 1; k < i.result.qp_statistics.size(); ++k)
      non_increasing = non_increasing &&
                       i.result.qp_statistics[k].tolerance <=
                         i.result.qp_statistics[k - 1].tolerance * (1 + 1e-12);
    check(non_increasing,
          "local_problem_test: inexact QP tolerances do not increase",
          i.result.qp_statistics.size());
    check(i.result.qp_statistics.back().tolerance <= 1e-9 &&
            i.result.qp_statistics.front().tolerance >= 1e-3,
          "local_problem_test: inexact: first QP loose, last one at the QP "
          "tolerance",
          i.result.qp_statistics.front().tolerance);
  }

  // a rigid-body problem (Capsules: W singular and slightly non-symmetric):
  // the plain first QP does not converge (reported, no crash); with the
  // Newton fallback off the automatic proximal loop takes over and
  // converges; by default the Newton method does, to the FCLIB error
  {
    const fclib::LocalProblem problem =
      fclib::read_local(FCLIB_TEST_DATA_DIR "Capsules-i125-1213.hdf5");
    qp::SolverParameters plain = prm;
    plain.solver               = "mpgp-bb";
    plain.tolerance            = 1e-7;
    plain.max_iterations       = 2000;
    contact::CoulombParameters loop;
    loop.tolerance = 1e-6;
    auto off       = coulomb_model;
    off.proximal   = fclib::Proximal::off;
    const auto p   = solve(problem, plain, loop, off);
    check(!p.result.converged && !p.result.proximal &&
            p.result.reason.find("did not converge") != std::string::npos,
          "Capsules, proximal off: not converged, said so",
          p.result.reason);
    auto proximal_qps                    = coulomb_model;
    proximal_qps.newton_after_plain_loop = false;
    const auto a = solve(problem, plain, loop, proximal_qps);
    check(a.result.converged && a.result.proximal &&
            a.result.proximal_reason.find("auto: the plain loop failed") !=
              std::string::npos,
          "Capsules, proximal auto: switched on after the plain loop failed, "
          "converged",
          a.result.proximal_reason + "; " + a.result.reason);
    check(a.result.fclib_error < 1e-6,
          "Capsules, proximal auto: FCLIB error",
          a.result.fclib_error);
    check(a.result.perturbations.back() <= 1e-6,
          "Capsules: perturbation of q at the end",
          a.result.perturbations.back());
    // the default: Newton after the failed plain loop, at 1e-8
    loop.tolerance = 1e-8;
    const auto n   = solve(problem, plain, loop, coulomb_model);
    check(n.result.converged && !n.result.proximal &&
            n.result.newton.converged &&
            n.result.proximal_reason.find("the Newton method solved it") !=
              std::string::npos,
          "Capsules, auto: the Newton method after the failed plain loop",
          n.result.proximal_reason);
    check(n.result.fclib_error <= 1e-8 &&
            n.result.fclib_error == fclib::fclib_error(problem, n.r),
          "Capsules, auto with Newton: FCLIB error <= 1e-8 (of the r returned)",
          n.result.fclib_error);
    // (36 steps on this machine; a tenth of the 1,004 proximal QPs)
    check(n.result.newton.steps <= 100,
          "Capsules, auto with Newton: steps",
          n.result.newton.steps);
  }

  // Capsules by De Saxce's fixed point over cone QPs at 1e-4: the shift
  // contracts about 0.5 per QP there (the Coulomb loop's psi 0.994): 13
  // QPs, 175 products (coulomb: 88 proximal QPs, 4382 products)
  {
    const fclib::LocalProblem problem =
      fclib::read_local(FCLIB_TEST_DATA_DIR "Capsules-i125-1213.hdf5");
    qp::SolverParameters qp = prm;
    qp.solver               = "mpgp";
    qp.tolerance            = 1e-4;
    contact::CoulombParameters loop;
    loop.tolerance = 1e-4;
    const auto d =
      solve(problem, qp, loop, with_model(fclib::Model::desaxce_fixed_point));
    check(d.result.converged && !d.result.proximal &&
            d.result.qp_statistics.size() <= 30,
          "Capsules, desaxce at 1e-4: converged by the plain loop, QPs",
          d.result.qp_statistics.size());
    check(d.result.fclib_error <= 2e-4,
          "Capsules, desaxce at 1e-4: FCLIB error <= 2e-4",
          d.result.fclib_error);
  }

  // spheres-in-a-box (256 contacts, W_s of rank 566 of 768): solved at 1e-4
  {
    const fclib::LocalProblem problem = fclib::read_as_local(
      FCLIB_TEST_DATA_DIR "spheres-in-a-box-98-i10000-256-10.hdf5");
    qp::SolverParameters qp = prm;
    qp.solver               = "mpgp-bb";
    qp.tolerance            = 1e-5;
    contact::CoulombParameters loop;
    loop.tolerance = 1e-4;
    const auto s   = solve(problem, qp, loop, coulomb_model);
    check(s.result.converged, "spheres-in-a-box: converged", s.result.reason);
    check(s.result.fclib_error <= 1e-4,
          "spheres-in-a-box: FCLIB error <= 1e-4",
          s.result.fclib_error);
    // at 1e-8 the plain loop stalls and (Newton fallback off) the
    // automatic proximal loop takes over; with the extrapolated centers it
    // converges in a few hundred proximal QPs (without: not within 1000,
    // FCLIB error 5.6e-8)
    qp.tolerance                         = 1e-9;
    loop.tolerance                       = 1e-8;
    auto proximal_qps                    = coulomb_model;
    proximal_qps.newton_after_plain_loop = false;
    const auto t = solve(problem, qp, loop, proximal_qps);
    check(t.result.converged && t.result.proximal,
          "spheres-in-a-box at 1e-8: converged by the proximal loop",
          t.result.proximal_reason + "; " + t.result.reason);
    check(t.result.fclib_error <= 1e-8,
          "spheres-in-a-box at 1e-8: FCLIB error <= 1e-8",
          t.result.fclib_error);
    // (Rho increase above 150, issue 20: more, cheaper proximal QPs, 641
    // and 57662 products; with 5000: 295 and 92694; without extrapolation
    // not converged in 5000)
    check(t.result.perturbations.size() <= 1500,
          "spheres-in-a-box at 1e-8: proximal QPs",
          t.result.perturbations.size());
    check(t.result.hessian_products <= 80000,
          "spheres-in-a-box at 1e-8: products with W",
          t.result.hessian_products);
    // by default the Newton method after the stalled plain loop
    const auto n = solve(problem, qp, loop, coulomb_model);
    check(n.result.converged && n.result.newton.converged &&
            !n.result.proximal && n.result.fclib_error <= 1e-8,
          "spheres-in-a-box at 1e-8, auto: solved by the Newton method",
          n.result.proximal_reason + "; " +
            std::to_string(n.result.fclib_error));
  }

  // write a problem with its solution and read both back
  {
    prm.solver                = "mpgp";
    const auto        problem = one_contact(2., 4., -4., 3., 0., 0.3);
    const auto        s       = solve(problem, prm, coulomb, coulomb_model);
    const std::string file    = "solve_local_round_trip.hdf5";
    fclib::write_local(file, problem, s.r, "test");
    const fclib::LocalProblem back = fclib::read_local(file);
    dealii::Vector<double>    q(back.q());
    q -= problem.q();
    check(back.n_contacts() == 1 && back.mu()[0] == 0.3 && q.l2_norm() == 0 &&
            back.W().el(1, 1) == 4.,
          "written problem read back",
          back.n_contacts());
    dealii::Vector<double> r_back = fclib::read_solution_r(file);
    check(r_back.size() == 3 && distance(r_back, {s.r(0), s.r(1), s.r(2)}) == 0,
          "written solution read back",
          r_back.size());
    std::filesystem::remove(file);
  }
  return test_tools::finish();
}
