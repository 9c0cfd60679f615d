/**
 * @file qpsolve_driver.h
 * Everything behind the `qpsolve` command: argument parsing, reading
 * PROBLEM.json, building the Problem (and SeparableSet, equality
 * constraints) from it, choosing the solver (SMALSE-M around it when the
 * problem has equalities; CGC with the bounds as linear inequalities), and
 * the JSON summary.  app/qpsolve.cc only calls run().
 *
 * Why in lib/tools (a library of the programs, not of the solvers): the
 * tests and the membrane benchmark run the same code path as the program,
 * and app/ stays thin, while lib/qp keeps only what a user of the solvers
 * links.
 */
#ifndef dualcontact_tools_qpsolve_driver_h
#define dualcontact_tools_qpsolve_driver_h

#include <qp/solver_parameters.h>

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace tools
  {
    /**
     * The qpsolve program.  Returns the exit code: 0 converged, 2 not
     * converged (any other reason), 1 bad input or usage (message on
     * @p err naming the file / field / option).
     */
    class QPSolveDriver
    {
    public:
      int
      run(const std::vector<std::string> &arguments,
          std::ostream                   &out,
          std::ostream                   &err) const;

      /**
       * `qpsolve --make-membrane --dir DIR [--variant thesis|permon]
       * [--h H] [--p P] [--load-scale S]`: write the membrane QP of
       * benchmark B4 as DIR/membrane.json (+ .mtx, .txt) and print n,
       * ||b|| and the closed-form extreme eigenvalues.
       */
      int
      make_membrane(const std::vector<std::string> &arguments,
                    std::ostream                   &out,
                    std::ostream                   &err) const;

      /// The usage text.
      static std::string
      usage();

      /**
       * Start from @p parameters instead of SolverParameters' defaults (the
       * program's `--prm FILE' and `--set "QP solver/Entry=value"', read
       * with the .prm names of SolverParameters::declare_parameters()); the
       * options (--solver, --tol, ...) still override them.
       */
      void
      set_base_parameters(const qp::SolverParameters &parameters);

    private:
      std::optional<qp::SolverParameters> base_parameters;
    };
  } // namespace tools
} // namespace dualcontact

#endif
