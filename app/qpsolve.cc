// qpsolve: solve a QP given as PROBLEM.json (see lib/qp/README.md and
// issue 3).  Thin: everything is in qp::QPSolveDriver.
#include <qp/qpsolve_driver.h>
#include <util/blas_kernels.h>

#include <deal.II/base/mpi.h>

#include <iostream>
#include <string>
#include <vector>

int
main(int argc, char **argv)
{
  // OpenBLAS' fast kernels on CPUs it does not recognise
  (void)dualcontact::util::blas_kernel_choice();
  // MPI (one process): Trilinos' AMG of --preconditioner amg needs it
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  try
  {
    const std::vector<std::string> arguments(argv + 1, argv + argc);
    return dualcontact::qp::QPSolveDriver().run(arguments,
                                                std::cout,
                                                std::cerr);
  }
  catch (const std::exception &e)
  {
    std::cerr << "qpsolve: " << e.what() << std::endl;
    return 1;
  }
}
