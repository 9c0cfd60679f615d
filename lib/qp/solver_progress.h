/**
 * @file solver_progress.h
 * What a QP solver tells a program while it runs, so that a long solve
 * shows signs of life without the library printing anything itself.
 */
#ifndef dualcontact_qp_solver_progress_h
#define dualcontact_qp_solver_progress_h

#include <functional>
#include <string>

namespace dualcontact
{
  namespace qp
  {
    /**
     * One report on a running solve: where it is (iterations, Hessian
     * products, time) and how far from its goal (the relative criterion
     * against the tolerance, the active set).
     */
    struct ProgressReport
    {
      /// the solver's name ("mprgp", ...)
      std::string   solver;
      unsigned int  iterations         = 0;
      unsigned long n_hessian_products = 0;
      /// relative criterion ||g_*|| / ||b|| at the current iterate
      double criterion = 0.;
      /// the relative tolerance the criterion is compared with
      double tolerance = 0.;
      /// wall time since the solve started [s]
      double elapsed = 0.;
      /// blocks of the constraint set active at the current iterate and
      /// all blocks; both -1 where counting them would need a collective
      /// operation (distributed vectors: the reports come at times that
      /// differ between the processes) or there are no constraints
      long n_active = -1;
      long n_blocks = -1;
      /// true for the report at the first checked iterate of a solve
      bool first = false;
    };

    /**
     * The hook a program sets in SolverParameters::progress: @p report is
     * called with a ProgressReport at the first checked iterate of every
     * solve and then whenever @p interval seconds have passed since the
     * last report (checked at every criterion evaluation, so a report
     * costs nothing between reports).  An empty @p report turns it off.
     */
    struct ProgressMonitor
    {
      std::function<void(const ProgressReport &)> report;
      /// seconds between two reports of one solve
      double interval = 5.;

      explicit operator bool() const
      {
        return static_cast<bool>(report);
      }
    };
  } // namespace qp
} // namespace dualcontact

#endif
