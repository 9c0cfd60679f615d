/**
 * @file fclibsolve_driver.h
 * Everything behind the `fclibsolve` command (lib/tools: the programs' code,
 * apart from the libraries the solvers live in).
 */
#ifndef dualcontact_tools_fclibsolve_driver_h
#define dualcontact_tools_fclibsolve_driver_h

#include <ostream>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace tools
  {
    /**
     * The `fclibsolve` program: read an FCLIB problem (local, or global
     * reduced to local form), solve it with the project's QP solvers
     * (Coulomb fixed point over Tresca QPs, or the cone QP), print the QP
     * outcome and the FCLIB accuracy measure, optionally write a JSON
     * summary and the problem with its solution as an FCLIB file.
     *
     * In lib/tools (not in app/) so that the tests run the same code.
     * Exit code: 0 converged, 2 not converged (reason and residuals printed),
     * 1 bad input or usage (message naming the file or option).
     */
    class FclibSolveDriver
    {
    public:
      int
      run(const std::vector<std::string> &arguments,
          std::ostream                   &out,
          std::ostream                   &err) const;

      static std::string
      usage();
    };
  } // namespace tools
} // namespace dualcontact

#endif
