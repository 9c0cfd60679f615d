// fclib::NewtonSolver (model newton: the semismooth Newton method on Alart
// and Curnier's equations in a proximal point loop): one contact with
// closed-form solutions in 3D and 2D (sliding, sticking, separated), found
// in at most 3 Newton steps without a proximal term; two contacts of
// different compliance coupled by W, against the Coulomb fixed point over
// QPs; the 8 FCLIB files at 1e-8, where the FCLIB error of the r returned
// must be at most the tolerance (the singular rigid-body W of Capsules and
// spheres-in-a-box through the proximal loop); the step limit is reported
// by name; bad parameters are refused by name.
#include <fclib/accuracy.h>
#include <fclib/fclib_file.h>
#include <fclib/local_solver.h>
#include <fclib/newton_solver.h>
#include <test_tools.h>

#include "data_files.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

using namespace dualcontact;
using test_tools::check;
using test_tools::distance;

namespace
{
  /** One contact, W = diag(k_n, k_t, ...), q given (2D or 3D). */
  fclib::LocalProblem
  one_contact(const unsigned int         dim,
              const double               k_n,
              const double               k_t,
              const std::vector<double> &q_values,
              const double               mu)
  {
    fclib::Triplets W(dim, dim);
    W.add(0, 0, k_n);
    for (unsigned int a = 1; a < dim; ++a)
      W.add(a, a, k_t);
    dealii::Vector<double> q(q_values.begin(), q_values.end());
    return fclib::LocalProblem(dim, W, q, {mu});
  }

  std::string
  scientific(const double x)
  {
    std::ostringstream s;
    s << std::scientific << std::setprecision(3) << x;
    return s.str();
  }

  struct Solved
  {
    fclib::NewtonSolver::Result result;
    dealii::Vector<double>      r;
  };

  Solved
  solve(const fclib::LocalProblem &problem, const double tolerance)
  {
    fclib::NewtonSolver::Parameters p;
    p.tolerance = tolerance;
    const fclib::NewtonSolver newton(problem, p);
    Solved                    out;
    out.r.reinit(problem.size());
    out.result = newton.solve(out.r);
    return out;
  }

  /** r to 1e-12, FCLIB error 0 to round-off, at most 3 plain steps. */
  void
  check_closed_form(const std::string         &name,
                    const fclib::LocalProblem &problem,
                    const std::vector<double> &expected)
  {
    const Solved s = solve(problem, 1e-14);
    check(s.result.converged && distance(s.r, expected) < 1e-12,
          name + ": r",
          distance(s.r, expected));
    check(s.result.steps <= 3 && s.result.proximal_iterations == 0,
          name + ": plain Newton steps",
          s.result.steps);
    check(s.result.fclib_error < 1e-14,
          name + ": FCLIB error",
          s.result.fclib_error);
  }
} // namespace


int
main()
{
  // sliding: k_n r_n = 4 (u_n = 0), the stick force 3 exceeds mu r_n = 1:
  // r_t = -1 against u_t = 1 * (-1) + 3 = 2 > 0
  check_closed_form("3D sliding",
                    one_contact(3, 2., 1., {-4., 3., 0.}, 0.5),
                    {2., -1., 0.});
  // sliding along a diagonal: r_t = -mu r_n (3, 4) / 5
  check_closed_form("3D sliding, oblique",
                    one_contact(3, 2., 1., {-4., 3., 4.}, 0.5),
                    {2., -0.6, -0.8});
  // sticking: the stick force 0.5 is within mu r_n = 1
  check_closed_form("3D sticking",
                    one_contact(3, 2., 1., {-4., 0.5, 0.}, 0.5),
                    {2., -0.5, 0.});
  // separated: q_n > 0, no force
  check_closed_form("3D separated",
                    one_contact(3, 2., 1., {1., 3., 0.}, 0.5),
                    {0., 0., 0.});
  check_closed_form("2D sliding",
                    one_contact(2, 2., 1., {-4., -3.}, 0.5),
                    {2., 1.});
  check_closed_form("2D sticking",
                    one_contact(2, 2., 1., {-4., 0.25}, 0.5),
                    {2., -0.25});

  // two contacts of compliance 1 and 100, coupled, one sliding: the same r
  // as the Coulomb fixed point over QPs
  {
    fclib::Triplets W(6, 6);
    const double    k[6] = {1., 2., 2., 100., 200., 200.};
    for (unsigned int i = 0; i < 6; ++i)
      W.add(i, i, k[i]);
    W.add(0, 3, 0.5);
    W.add(3, 0, 0.5);
    dealii::Vector<double> q(6);
    q(0) = -4.;
    q(1) = 3.;
    q(3) = -100.;
    q(4) = 20.;
    q(5) = 20.;
    const fclib::LocalProblem problem(3, W, q, {0.5, 0.3});
    const Solved              n = solve(problem, 1e-13);
    qp::SolverParameters      prm;
    prm.solver    = "mpgp";
    prm.tolerance = 1e-12;
    contact::CoulombParameters coulomb;
    coulomb.tolerance = 1e-12;
    fclib::LocalSolver::Parameters loop;
    const fclib::LocalSolver       qps(problem, prm, coulomb, loop);
    dealii::Vector<double>         r(6);
    const auto                     result = qps.solve(r);
    dealii::Vector<double>         difference(r);
    difference -= n.r;
    check(n.result.converged && result.converged &&
            difference.l2_norm() < 1e-9 * r.l2_norm(),
          "two contacts: Newton against the Coulomb fixed point over QPs",
          difference.l2_norm() / r.l2_norm());
  }

  // the FCLIB files at 1e-8: the error of the r returned, as reported
  for (const std::string &name : fclib_test_data::names)
  {
    const fclib::LocalProblem problem =
      fclib::read_as_local(FCLIB_TEST_DATA_DIR + name + ".hdf5");
    const Solved s     = solve(problem, 1e-8);
    const double error = fclib::fclib_error(problem, s.r);
    check(s.result.converged && error <= 1e-8 && error == s.result.fclib_error,
          name + ": converged to FCLIB error <= 1e-8",
          s.result.reason + ", error " + scientific(error));
    // the singular rigid-body W: the plain method fails, the proximal
    // loop converges
    if (name == "Capsules-i125-1213" ||
        name == "spheres-in-a-box-98-i10000-256-10")
      check(s.result.proximal_iterations > 0,
            name + ": through the proximal loop",
            s.result.proximal_iterations);
  }

  // a step limit that cannot be met: not converged, and said so
  {
    const fclib::LocalProblem problem = fclib::read_as_local(
      FCLIB_TEST_DATA_DIR "spheres-in-a-box-98-i10000-256-10.hdf5");
    fclib::NewtonSolver::Parameters p;
    p.tolerance = 1e-8;
    p.max_steps = 5;
    const fclib::NewtonSolver newton(problem, p);
    dealii::Vector<double>    r(problem.size());
    const auto                result = newton.solve(r);
    check(!result.converged && result.steps == 5 &&
            result.reason.find("Newton/Maximum steps") != std::string::npos,
          "step limit: not converged, the parameter named",
          result.reason);
  }

  // bad parameters name themselves
  {
    const auto problem = one_contact(3, 2., 1., {-4., 3., 0.}, 0.5);
    auto       refused =
      [&](fclib::NewtonSolver::Parameters p, const std::string &name)
    {
      try
      {
        const fclib::NewtonSolver newton(problem, p);
      }
      catch (const dealii::ExceptionBase &e)
      {
        return std::string(e.what()).find(name) != std::string::npos;
      }
      return false;
    };
    fclib::NewtonSolver::Parameters p;
    p.sigma_reduction = 0;
    check(refused(p, "Newton/Sigma reduction"), "Sigma reduction 0 refused", 0);
    p           = {};
    p.sigma_min = 2 * p.sigma;
    check(refused(p, "Newton/Minimum sigma"),
          "Minimum sigma > Sigma refused",
          0);
    p        = {};
    p.armijo = 0.5;
    check(refused(p, "Newton/Armijo constant"),
          "Armijo constant 0.5 refused",
          0);
    p            = {};
    p.rho_factor = 0;
    check(refused(p, "Newton/Rho factor"), "Rho factor 0 refused", 0);
  }
  return test_tools::finish();
}
