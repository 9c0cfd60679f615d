// LocalSolver and the FCLIB error on problems with closed-form solutions:
// one contact with W = diag(k_n, k_t, k_t), sliding and sticking; the cone
// QP (a relaxation: the projection of -q onto the cone for W = I); write and
// read back a problem with its solution.
#include <fclib/accuracy.h>
#include <fclib/fclib_file.h>
#include <fclib/local_solver.h>
#include <test_tools.h>

#include <cmath>
#include <filesystem>

using namespace dualcontact;
using test_tools::check;

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

  double
  distance(const dealii::Vector<double> &a, const std::vector<double> &b)
  {
    double s = 0;
    for (unsigned int i = 0; i < a.size(); ++i)
      s += std::pow(a(i) - b[i], 2);
    return std::sqrt(s);
  }
} // namespace

int
main()
{
  qp::SolverParameters       prm;
  contact::CoulombParameters coulomb;
  prm.tolerance     = 1e-12;
  coulomb.tolerance = 1e-12;

  for (const std::string solver : {"mpgp", "mpgp-bb", "spg-qp", "apgd"})
  {
    prm.solver = solver;
    // sliding: r_n = -q_n / k_n = 2; stick would need |r_t| = |q_t| / k_t
    // = 1 > mu r_n = 0.6, so r_t = -0.6 q_t/|q_t|, u_n = 0, u_t || q_t
    {
      const auto         problem = one_contact(2., 4., -4., 3., 4. * 0, 0.3);
      fclib::LocalSolver s(problem,
                           prm,
                           coulomb,
                           fclib::Model::coulomb_fixed_point);
      dealii::Vector<double> r(3);
      const auto             result = s.solve(r);
      check(result.converged, solver + " slip: converged", result.reason);
      check(distance(r, {2., -0.6, 0.}) < 1e-9,
            solver + " slip: |r - r*|",
            distance(r, {2., -0.6, 0.}));
      check(result.fclib_error < 1e-9,
            solver + " slip: FCLIB error",
            result.fclib_error);
      check(result.coulomb_changes.size() <= 4,
            solver + " slip: Coulomb iterations",
            result.coulomb_changes.size());
    }
    // sticking, tangential load at 45 degrees: r = -W^-1 q
    {
      const auto             problem = one_contact(1., 2., -1., 0.2, 0.2, 0.5);
      fclib::LocalSolver     s(problem,
                           prm,
                           coulomb,
                           fclib::Model::coulomb_fixed_point);
      dealii::Vector<double> r(3);
      const auto             result = s.solve(r);
      check(result.converged, solver + " stick: converged", result.reason);
      check(distance(r, {1., -0.1, -0.1}) < 1e-9,
            solver + " stick: |r - r*|",
            distance(r, {1., -0.1, -0.1}));
      check(result.fclib_error < 1e-9,
            solver + " stick: FCLIB error",
            result.fclib_error);
    }
    // separation: q_n > 0, r = 0
    {
      const auto             problem = one_contact(1., 1., 0.5, 0.2, -0.1, 0.5);
      fclib::LocalSolver     s(problem,
                           prm,
                           coulomb,
                           fclib::Model::coulomb_fixed_point);
      dealii::Vector<double> r(3);
      const auto             result = s.solve(r);
      check(result.converged && r.l2_norm() < 1e-12,
            solver + " separation: r = 0",
            r.l2_norm());
    }
    // the cone QP with W = I: r = P_K(-q), a relaxation whose FCLIB error
    // is not zero when the contact slides
    {
      const auto             problem = one_contact(1., 1., -1., 0.5, 0., 0.3);
      fclib::LocalSolver     s(problem, prm, coulomb, fclib::Model::cone);
      dealii::Vector<double> r(3);
      const auto             result = s.solve(r);
      const double           a      = (1. + 0.3 * 0.5) / (1. + 0.09);
      check(result.converged, solver + " cone: converged", result.reason);
      check(distance(r, {a, -0.3 * a, 0.}) < 1e-9,
            solver + " cone: r = P_K(-q), |r - r*|",
            distance(r, {a, -0.3 * a, 0.}));
      // the Coulomb solution is (1, -0.3, 0): the relaxation differs
      check(result.fclib_error > 1e-2,
            solver + " cone: FCLIB error of the relaxation",
            result.fclib_error);
    }
  }

  // mprgp takes mu = 0 (bounds only) and refuses discs with a clear message
  {
    prm.solver                     = "mprgp";
    const auto             problem = one_contact(2., 4., -4., 3., 0., 0.);
    fclib::LocalSolver     s(problem,
                         prm,
                         coulomb,
                         fclib::Model::coulomb_fixed_point);
    dealii::Vector<double> r(3);
    const auto             result = s.solve(r);
    check(result.converged && distance(r, {2., 0., 0.}) < 1e-12,
          "mprgp frictionless: r = (2, 0, 0)",
          distance(r, {2., 0., 0.}));
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

  // a rigid-body problem (Capsules: W singular and slightly non-symmetric):
  // the plain first QP does not converge (reported, no crash); the proximal
  // loop with the lagged antisymmetric part of W converges
  {
    const fclib::LocalProblem problem =
      fclib::read_local(FCLIB_TEST_DATA_DIR "Capsules-i125-1213.hdf5");
    qp::SolverParameters plain = prm;
    plain.solver               = "mpgp";
    plain.tolerance            = 1e-8;
    plain.max_iterations       = 2000;
    contact::CoulombParameters loop;
    loop.tolerance      = 1e-6;
    loop.max_iterations = 3000;
    {
      fclib::LocalSolver     s(problem,
                           plain,
                           loop,
                           fclib::Model::coulomb_fixed_point);
      dealii::Vector<double> r(problem.size());
      const auto             result = s.solve(r);
      check(!result.converged &&
              result.reason.find("did not converge") != std::string::npos,
            "Capsules, plain QP: not converged, said so",
            result.reason);
    }
    {
      plain.max_iterations = 10000;
      fclib::LocalSolver     s(problem,
                           plain,
                           loop,
                           fclib::Model::coulomb_fixed_point,
                           fclib::FirstIterate::bonded,
                           0.1);
      dealii::Vector<double> r(problem.size());
      const auto             result = s.solve(r);
      check(result.converged,
            "Capsules, proximal 0.1: converged",
            result.reason);
      check(result.fclib_error < 1e-6,
            "Capsules, proximal 0.1: FCLIB error",
            result.fclib_error);
    }
  }

  // write a problem with its solution and read both back
  {
    prm.solver                     = "mpgp";
    const auto             problem = one_contact(2., 4., -4., 3., 0., 0.3);
    fclib::LocalSolver     s(problem,
                         prm,
                         coulomb,
                         fclib::Model::coulomb_fixed_point);
    dealii::Vector<double> r(3);
    s.solve(r);
    const std::string file = "solve_local_round_trip.hdf5";
    fclib::write_local(file, problem, r, "test");
    const fclib::LocalProblem back = fclib::read_local(file);
    dealii::Vector<double>    q(back.q());
    q -= problem.q();
    check(back.n_contacts() == 1 && back.mu()[0] == 0.3 && q.l2_norm() == 0 &&
            back.W().el(1, 1) == 4.,
          "written problem read back",
          back.n_contacts());
    dealii::Vector<double> r_back = fclib::read_solution_r(file);
    check(r_back.size() == 3 && distance(r_back, {r(0), r(1), r(2)}) == 0,
          "written solution read back",
          r_back.size());
    std::filesystem::remove(file);
  }
  return test_tools::finish();
}
