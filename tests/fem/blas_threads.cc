// `Stiffness solver / BLAS threads` (fem::StiffnessSolver::
// apply_blas_threads, util::automatic_blas_threads):
//  - under MPI (more than one process) automatic gives one thread;
//  - OPENBLAS_NUM_THREADS or OMP_NUM_THREADS set by the user are kept
//    (threads 0: nothing changed) and named in the reason;
//  - otherwise between one thread and the cores of the CPU set, the reason
//    naming the load average;
//  - a number is given to OpenBLAS as it is (when the BLAS is OpenBLAS);
//  - `0', `two', `1.5' and an empty value are errors naming the parameter.

#include <deal.II/base/parameter_handler.h>

#include <fem/stiffness_solver.h>
#include <util/blas_kernels.h>

#include <test_tools.h>

#include <sched.h>

#include <cstdlib>
#include <iostream>
#include <string>

using namespace dualcontact;
using test_tools::check;

namespace
{
  /** apply_blas_threads() on `BLAS threads = @p value'. */
  std::string
  apply(const std::string &value)
  {
    dealii::ParameterHandler prm;
    fem::StiffnessSolver::declare_parameters(prm);
    prm.enter_subsection("Stiffness solver");
    prm.set("BLAS threads", value);
    prm.leave_subsection();
    return fem::StiffnessSolver::apply_blas_threads(prm);
  }

  bool
  throws_naming_parameter(const std::string &value)
  {
    try
    {
      apply(value);
    }
    catch (const std::exception &e)
    {
      const std::string what = e.what();
      return what.find("BLAS threads") != std::string::npos &&
             what.find("Stiffness solver") != std::string::npos;
    }
    return false;
  }
} // namespace


int
main()
{
  const util::BlasThreadChoice mpi = util::automatic_blas_threads(4);
  check(mpi.threads == 1, "automatic under MPI (4 processes): threads", 1);

  setenv("OPENBLAS_NUM_THREADS", "1", 1);
  const util::BlasThreadChoice user = util::automatic_blas_threads(1);
  check(user.threads == 0 &&
          user.reason == "OPENBLAS_NUM_THREADS=1 set by the user",
        "the user's OPENBLAS_NUM_THREADS kept",
        user.reason);
  unsetenv("OPENBLAS_NUM_THREADS");
  unsetenv("OMP_NUM_THREADS");

  cpu_set_t cpus;
  CPU_ZERO(&cpus);
  sched_getaffinity(0, sizeof(cpus), &cpus);
  const int                    cores = CPU_COUNT(&cpus);
  const util::BlasThreadChoice own   = util::automatic_blas_threads(1);
  check(own.threads >= 1 && own.threads <= cores &&
          own.reason.rfind("automatic: load average ", 0) == 0,
        "automatic on one process: between 1 and the " + std::to_string(cores) +
          " cores",
        std::to_string(own.threads) + ", " + own.reason);

  const std::string three = apply("3");
  if (util::blas_threads() > 0) // OpenBLAS
    check(util::blas_threads() == 3 && three == "3 (set in the input)",
          "BLAS threads = 3 given to OpenBLAS",
          three);
  apply("1");

  for (const std::string bad : {"0", "two", "1.5", "", "-2"})
    check(throws_naming_parameter(bad),
          "BLAS threads = `" + bad + "': an error naming the parameter",
          bad);
  return test_tools::finish();
}
