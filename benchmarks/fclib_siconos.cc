// Siconos' fc3d solvers and dualcontact's QP solvers on the same FCLIB
// problems (issue 7).  Built only when Debian's libsiconos-numerics-dev is
// installed (Debian builds Siconos without its FCLIB reader: the problems
// are read by lib/fclib through libfclib and handed to Siconos as a dense
// W, q, mu).  Every result is judged by the same accuracy measure,
// fclib::fclib_error, computed here from the returned r.
//
//   bench_fclib_siconos [--tol T]... [--max-iter N] [--siconos-max-iter N]
//                       [--time-limit S] [--repeat-below S]
//                       [--out FILE.csv] [--solvers a,b,...] FILE.hdf5...
//
// Limits: --max-iter per QP of ours (default 10000), --siconos-max-iter
// for Siconos' outer iterations (default 2000; a Newton iteration of NSN_AC
// factorizes the dense W).  Ours: QP tolerance 0.1 tol, Coulomb tolerance
// tol (at most 100 plain iterations; the proximal loop, switched on when
// the plain one fails, at most 1000); coulomb/NAME with LocalSolver's
// defaults (inexact QPs, automatic proximal point, W dense or sparse by
// its density), exact/NAME with every QP to the QP tolerance and no
// proximal point, auto/NAME what `fclibsolve FILE --tol T --solver NAME'
// runs (QP and Coulomb tolerance T, the defaults: the Newton method after a
// failed plain loop), newton/ac model newton (the semismooth Newton method
// on Alart-Curnier's equations, to an FCLIB error <= T).  Siconos gets W
// dense.  Every solve (Siconos' and ours)
// runs in a child process (Siconos aborts on some inputs) stopped after
// --time-limit seconds (default 300), counted as a failure; a solve
// shorter than --repeat-below seconds (default 1) is repeated from its cold
// start (at most 5 runs, while the total stays below that) and the fastest
// run is reported, for every solver alike.
//
// One CSV line per (problem, tolerance, solver): the solver's own verdict,
// iterations as the solver counts them (Siconos: its outer iterations, e.g.
// Gauss-Seidel sweeps; ours: QP iterations summed over the Coulomb loop),
// products with W (ours only), CPU time (time_s: every solve runs
// single-threaded in its own process, so its CPU time is its work, little
// disturbed by other jobs on a shared machine), wall time (wall_s; a
// time-limited run: the limit) and the final FCLIB error.
#include <deal.II/base/timer.h>
#include <util/blas_kernels.h>

#include <fclib/accuracy.h>
#include <fclib/fclib_file.h>
#include <fclib/local_solver.h>
#include <fclib/newton_solver.h>

#include <siconos/numerics/FrictionContactProblem.h>
#include <siconos/numerics/Friction_cst.h>
#include <siconos/numerics/NonSmoothDrivers.h>
#include <siconos/numerics/NumericsMatrix.h>
#include <siconos/numerics/SolverOptions.h>

#include <sys/wait.h>

#include <cmath>
#include <csignal>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <unistd.h>

using namespace dualcontact;

namespace
{
  /** CPU time of this process [s]. */
  double
  cpu_seconds()
  {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
  }

  struct Outcome
  {
    bool          solver_converged = false;
    unsigned long iterations       = 0;
    unsigned long products         = 0;
    /** CPU time of the solve [s] (single-threaded child process). */
    double time = 0;
    /** Wall time of the solve [s]. */
    double      wall  = 0;
    double      error = 0;
    std::string note;
  };

  const std::map<std::string, int> siconos_solvers = {
    {"NSGS", SICONOS_FRICTION_3D_NSGS},
    {"NSN_AC", SICONOS_FRICTION_3D_NSN_AC},
    {"PROX", SICONOS_FRICTION_3D_PROX},
    {"TFP", SICONOS_FRICTION_3D_TFP},
    {"VI_EG", SICONOS_FRICTION_3D_VI_EG},
    {"ADMM", SICONOS_FRICTION_3D_ADMM}};

  /**
   * Repeats a short run: @p run again (from its cold start) while the
   * total time is below @p repeat_below seconds, at most 5 runs; the
   * outcome of the fastest run.  Short runs (a few milliseconds) on a busy
   * machine are otherwise mostly noise; every solver is treated alike.
   */
  template <typename Run>
  Outcome
  fastest_of(const Run &run, const double repeat_below)
  {
    Outcome best  = run();
    double  total = best.time;
    for (int k = 1; k < 5 && total < repeat_below; ++k)
    {
      const Outcome o = run();
      total += o.time;
      if (o.time < best.time)
        best = o;
    }
    return best;
  }

  Outcome
  run_siconos(const fclib::LocalProblem &problem,
              const std::string         &name,
              const double               tol,
              const int                  max_iter)
  {
    const int       n = problem.size();
    NumericsMatrix *W = NM_create(NM_DENSE, n, n);
    for (int k = 0; k < n * n; ++k)
      W->matrix0[k] = 0;
    for (int i = 0; i < n; ++i)
      for (auto it = problem.W().begin(i); it != problem.W().end(i); ++it)
        W->matrix0[i + static_cast<long>(it->column()) * n] = it->value();
    std::vector<double>     q(problem.q().begin(), problem.q().end());
    std::vector<double>     mu(problem.mu());
    FrictionContactProblem *fc = frictionContactProblem_new_with_data(
      3, problem.n_contacts(), W, q.data(), mu.data());
    SolverOptions *options = solver_options_create(siconos_solvers.at(name));
    options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
    options->dparam[SICONOS_DPARAM_TOL]      = tol;
    std::vector<double> r(n, 0.), u(n, 0.);

    dealii::Timer timer;
    const double  cpu  = cpu_seconds();
    const int     info = fc3d_driver(fc, r.data(), u.data(), options);
    Outcome       out;
    out.time             = cpu_seconds() - cpu;
    out.wall             = timer.wall_time();
    out.solver_converged = (info == 0);
    out.iterations       = options->iparam[SICONOS_IPARAM_ITER_DONE];
    std::ostringstream note;
    note << "info " << info << ", own residual "
         << options->dparam[SICONOS_DPARAM_RESIDU];
    out.note = note.str();
    dealii::Vector<double> rr(r.begin(), r.end());
    bool                   finite = true;
    for (const double v : r)
      finite = finite && std::isfinite(v);
    out.error = finite ? fclib::fclib_error(problem, rr) : INFINITY;
    solver_options_delete(options);
    // the problem does not own q and mu here: detach them before freeing
    fc->q  = nullptr;
    fc->mu = nullptr;
    frictionContactProblem_free(fc);
    return out;
  }

  /**
   * @p run in a child process: Siconos ends the process on some inputs (an
   * assert on a zero diagonal block of W, e.g. a contact node whose dofs
   * are all prescribed) and no solver has a time limit, so each solve (of
   * Siconos and ours alike) is isolated and stopped after @p time_limit
   * seconds (a failure).
   */
  template <typename Run>
  Outcome
  run_isolated(const Run &run, const double time_limit)
  {
    int fds[2];
    if (pipe(fds) != 0)
      return run();
    dealii::Timer timer;
    const pid_t   child = fork();
    if (child == 0)
    {
      close(fds[0]);
      const Outcome o          = run();
      const double  numbers[6] = {double(o.solver_converged),
                                  double(o.iterations),
                                  o.time,
                                  o.error,
                                  double(o.products),
                                  o.wall};
      (void)!write(fds[1], numbers, sizeof(numbers));
      const std::string note = o.note.substr(0, 200);
      (void)!write(fds[1], note.c_str(), note.size());
      close(fds[1]);
      _exit(0);
    }
    close(fds[1]);
    int  status = 0;
    bool done   = false;
    while (timer.wall_time() < time_limit)
    {
      if (waitpid(child, &status, WNOHANG) == child)
      {
        done = true;
        break;
      }
      usleep(20000);
    }
    Outcome out;
    if (!done)
    {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
      out.time  = timer.wall_time();
      out.wall  = out.time;
      out.error = INFINITY;
      out.note  = "stopped after the time limit of " +
                 std::to_string(int(time_limit)) + " s";
      close(fds[0]);
      return out;
    }
    double  numbers[6];
    ssize_t got = read(fds[0], numbers, sizeof(numbers));
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 ||
        got != sizeof(numbers))
    {
      out.time  = timer.wall_time();
      out.error = INFINITY;
      out.note  = WIFSIGNALED(status) ?
                    std::string("the solver ended the process: ") +
                     strsignal(WTERMSIG(status)) :
                    "the solver ended the process";
      close(fds[0]);
      return out;
    }
    char    buffer[256];
    ssize_t length = read(fds[0], buffer, sizeof(buffer) - 1);
    buffer[std::max<ssize_t>(length, 0)] = 0;
    close(fds[0]);
    out.solver_converged = numbers[0] != 0;
    out.iterations       = static_cast<unsigned long>(numbers[1]);
    out.time             = numbers[2];
    out.error            = numbers[3];
    out.products         = static_cast<unsigned long>(numbers[4]);
    out.wall             = numbers[5];
    out.note             = buffer;
    return out;
  }

  /** model newton: fclib::NewtonSolver to an FCLIB error <= @p tol. */
  Outcome
  run_newton(const fclib::LocalProblem &problem, const double tol)
  {
    fclib::NewtonSolver::Parameters parameters;
    parameters.tolerance = tol;
    Outcome out;
    try
    {
      const fclib::NewtonSolver newton(problem, parameters);
      dealii::Vector<double>    r(problem.size());
      const double              cpu    = cpu_seconds();
      const auto                result = newton.solve(r);
      out.time                         = cpu_seconds() - cpu;
      out.solver_converged             = result.converged;
      out.iterations                   = result.steps;
      out.products                     = result.products;
      out.wall                         = result.wall_time;
      out.error                        = result.fclib_error;
      out.note                         = result.reason;
    }
    catch (const std::exception &e)
    {
      out.error = INFINITY;
      out.note  = e.what();
    }
    return out;
  }


  Outcome
  run_ours(const fclib::LocalProblem &problem,
           const std::string         &name,
           const double               tol,
           const int                  max_iter)
  {
    // name: "<loop>/<qp solver>": coulomb/NAME the Coulomb fixed point with
    // LocalSolver's defaults (inexact QPs, proximal point switched on if
    // the plain loop fails), exact/NAME every QP to the QP tolerance and no
    // proximal point (the first version's loop), cone/NAME the cone QP
    const std::string loop   = name.substr(0, name.find('/'));
    const std::string solver = name.substr(name.find('/') + 1);
    if (loop == "newton")
      return run_newton(problem, tol);
    fclib::LocalSolver::Parameters parameters;
    if (loop == "cone")
      parameters.model = fclib::Model::cone;
    else if (loop == "exact")
    {
      parameters.inexact  = false;
      parameters.proximal = fclib::Proximal::off;
    }
    else
      AssertThrow(loop == "coulomb" || loop == "auto",
                  dealii::ExcMessage("unknown loop " + loop));
    // the QPs 10 times tighter than the target, so that the FCLIB error of
    // the fixed point can reach the target tolerance; auto/NAME: what
    // `fclibsolve FILE --tol T --solver NAME' runs (QP and Coulomb
    // tolerance T, every other setting at its default)
    qp::SolverParameters prm;
    prm.solver         = solver;
    prm.tolerance      = loop == "auto" ? tol : 0.1 * tol;
    prm.max_iterations = max_iter;
    contact::CoulombParameters coulomb;
    coulomb.tolerance = tol;
    if (loop != "auto")
      coulomb.max_iterations = 100;
    Outcome out;
    try
    {
      fclib::LocalSolver     s(problem, prm, coulomb, parameters);
      dealii::Vector<double> r(problem.size());
      const double           cpu    = cpu_seconds();
      const auto             result = s.solve(r);
      out.time                      = cpu_seconds() - cpu;
      out.solver_converged          = result.converged;
      out.iterations                = result.iterations;
      out.products                  = result.hessian_products;
      out.wall                      = result.wall_time;
      out.error                     = result.fclib_error;
      out.note                      = result.reason;
      if (result.proximal)
        out.note += " [proximal " + result.proximal_reason.substr(0, 40) + "]";
    }
    catch (const std::exception &e)
    {
      out.error = INFINITY;
      out.note  = e.what();
    }
    return out;
  }


  std::string
  csv_text(std::string s)
  {
    for (char &c : s)
      if (c == ',' || c == '\n')
        c = ';';
    return s;
  }
} // namespace

int
main(int argc, char **argv)
{
  // OpenBLAS' fast kernels on CPUs it does not recognise
  (void)dualcontact::util::blas_kernel_choice();
  std::vector<double>      tolerances;
  std::vector<std::string> files;
  std::string              out_file = "fclib_siconos.csv";
  int                      max_iter = 10000, siconos_max_iter = 2000;
  double                   time_limit = 300, repeat_below = 1.;
  std::vector<std::string> solvers = {"NSGS",
                                      "NSN_AC",
                                      "PROX",
                                      "TFP",
                                      "VI_EG",
                                      "ADMM",
                                      "coulomb/mpgp",
                                      "coulomb/mpgp-bb",
                                      "coulomb/spg-qp",
                                      "coulomb/apgd",
                                      "exact/mpgp-bb",
                                      "cone/mpgp-bb",
                                      "auto/mpgp",
                                      "newton/ac"};
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--tol" && i + 1 < argc)
      tolerances.push_back(std::stod(argv[++i]));
    else if (a == "--max-iter" && i + 1 < argc)
      max_iter = std::stoi(argv[++i]);
    else if (a == "--time-limit" && i + 1 < argc)
      time_limit = std::stod(argv[++i]);
    else if (a == "--repeat-below" && i + 1 < argc)
      repeat_below = std::stod(argv[++i]);
    else if (a == "--siconos-max-iter" && i + 1 < argc)
      siconos_max_iter = std::stoi(argv[++i]);
    else if (a == "--out" && i + 1 < argc)
      out_file = argv[++i];
    else if (a == "--solvers" && i + 1 < argc)
    {
      solvers.clear();
      std::stringstream list(argv[++i]);
      for (std::string s; std::getline(list, s, ',');)
        solvers.push_back(s);
    }
    else
      files.push_back(a);
  }
  if (tolerances.empty())
    tolerances = {1e-4, 1e-8};
  if (files.empty())
  {
    std::cerr << "usage: bench_fclib_siconos [--tol T]... [--max-iter N] "
                 "[--out FILE.csv] [--solvers a,b] FILE.hdf5...\n";
    return 1;
  }
  std::ofstream csv(out_file);
  csv << "problem,contacts,tolerance,solver,solver_converged,iterations,"
         "products,time_s,wall_s,fclib_error,note\n";
  for (const std::string &file : files)
  {
    const fclib::LocalProblem problem = fclib::read_as_local(file);
    const std::string         name    = file.substr(file.find_last_of('/') + 1);
    for (const double tol : tolerances)
      for (const std::string &solver : solvers)
      {
        const bool ours = solver.find('/') != std::string::npos;
        if (!ours && !siconos_solvers.count(solver))
        {
          std::cerr << "unknown solver " << solver << "\n";
          return 1;
        }
        const Outcome o = run_isolated(
          [&]()
          {
            return fastest_of(
              [&]()
              {
                return ours ?
                         run_ours(problem, solver, tol, max_iter) :
                         run_siconos(problem, solver, tol, siconos_max_iter);
              },
              repeat_below);
          },
          time_limit);
        csv << name << "," << problem.n_contacts() << "," << tol << ","
            << solver << "," << o.solver_converged << "," << o.iterations << ","
            << o.products << "," << std::setprecision(6) << o.time << ","
            << o.wall << "," << std::setprecision(6) << o.error << ","
            << csv_text(o.note) << std::endl;
        std::cout << std::left << std::setw(48) << name << " tol "
                  << std::setw(6) << tol << std::setw(18) << solver
                  << (o.solver_converged ? "conv " : "FAIL ") << std::setw(8)
                  << o.iterations << std::setw(12) << o.time << o.error << "  "
                  << o.note.substr(0, 60) << std::endl;
      }
  }
  return 0;
}
