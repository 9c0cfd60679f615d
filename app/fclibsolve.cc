// fclibsolve: solve an FCLIB frictional contact problem with dualcontact's
// QP solvers (issue 7).  Thin: everything is in tools::FclibSolveDriver.
#include <tools/fclibsolve_driver.h>
#include <util/blas_kernels.h>

#include <iostream>
#include <string>
#include <vector>

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
  try
  {
    const std::vector<std::string> arguments(argv + 1, argv + argc);
    return dualcontact::tools::FclibSolveDriver().run(arguments,
                                                      std::cout,
                                                      std::cerr);
  }
  catch (const std::exception &e)
  {
    std::cerr << "fclibsolve: " << e.what() << std::endl;
    return 1;
  }
}
