// qpsolve: solve a QP given as PROBLEM.json (see lib/qp/README.md and
// issue 3).  Thin: everything is in tools::QPSolveDriver; this file only reads
// `--prm FILE' and `--set "QP solver/Entry=value"' (dualcontact's parameter
// names) into the driver's starting parameters.
#include <io/parameter_file.h>
#include <qp/problem_io.h>
#include <qp/solver_parameters.h>
#include <tools/qpsolve_driver.h>
#include <util/blas_kernels.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <iostream>
#include <string>
#include <vector>

namespace
{
  /**
   * Take `--prm FILE' and `--set TEXT' out of @p arguments; if there were
   * any, read them into @p driver's starting parameters: subsection `QP
   * solver' as dualcontact declares it (default solver auto, as qpsolve's),
   * the file and the settings checked like dualcontact's.
   */
  void
  read_parameter_options(std::vector<std::string>          &arguments,
                         dualcontact::tools::QPSolveDriver &driver)
  {
    using namespace dualcontact;
    std::string                        file;
    std::vector<io::ParameterOverride> overrides;
    std::vector<std::string>           rest;
    for (std::size_t k = 0; k < arguments.size(); ++k)
    {
      const std::string &argument = arguments[k];
      const bool takes_value      = argument == "--prm" || argument == "--set";
      if (takes_value && k + 1 >= arguments.size())
        throw std::runtime_error("option " + argument + " needs a value");
      if (argument == "--prm")
        file = arguments[++k];
      else if (argument == "--set")
        overrides.push_back(io::parse_parameter_override(arguments[++k]));
      else
        rest.push_back(argument);
    }
    arguments = rest;
    if (file.empty() && overrides.empty())
      return;
    dealii::ParameterHandler prm;
    qp::SolverParameters::declare_parameters(prm);
    if (!file.empty())
      io::parse_parameter_file(prm, file, false);
    io::apply_parameter_overrides(prm, overrides, false);
    qp::SolverParameters parameters;
    parameters.parse_parameters(prm);
    driver.set_base_parameters(parameters);
  }
} // namespace


int
main(int argc, char **argv)
{
  // OpenBLAS' fast kernels on CPUs it does not recognise
  (void)dualcontact::util::blas_kernel_choice();
  // OpenBLAS' threads on the cores the load leaves idle, unless the user
  // set OPENBLAS_NUM_THREADS / OMP_NUM_THREADS (util/blas_kernels.h: its
  // waiting threads spin and slow a busy machine down)
  dualcontact::util::use_blas_threads(
    dualcontact::util::automatic_blas_threads(1));
  // MPI (one process): Trilinos' AMG of --preconditioner amg needs it
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  try
  {
    std::vector<std::string>          arguments(argv + 1, argv + argc);
    dualcontact::tools::QPSolveDriver driver;
    read_parameter_options(arguments, driver);
    return driver.run(arguments, std::cout, std::cerr);
  }
  catch (const std::exception &e)
  {
    std::cerr << "qpsolve: " << dualcontact::qp::plain_message(e) << std::endl;
    return 1;
  }
}
