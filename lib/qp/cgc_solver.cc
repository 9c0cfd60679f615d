#include <qp/cgc.h>
#include <qp/cgc_solver.h>
#include <qp/kkt_residuals.h>
#include <qp/separable_set.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <limits>
#include <memory>

namespace dualcontact
{
  namespace qp
  {
    namespace
    {
      /// CGC behind the solver interface; see cgc_solver_entry().
      template <typename VectorType>
      class CGCSolver : public SolverBase<VectorType>
      {
      public:
        explicit CGCSolver(const SolverParameters &parameters)
            : SolverBase<VectorType>("cgc", parameters)
        {
        }

        SolverStatistics
        solve(const Problem<VectorType> &problem, VectorType &x) override
        {
          AssertThrow(!problem.equality,
                      dealii::ExcMessage("cgc: equality constraints are not "
                                         "supported (use another `QP "
                                         "solver/Solver')."));
          AssertThrow(!problem.constraints ||
                        problem.constraints->only_bounds_and_boxes(),
                      dealii::ExcMessage(
                        "cgc: only bound and box constraints "
                        "(frictionless or 2D Tresca problems); "
                        "use another `QP solver/Solver' for "
                        "discs, ellipses or cones."));
          const SolverParameters &prm = this->parameters();
          AssertThrow(prm.stopping_criterion == StoppingCriterion::projected,
                      dealii::ExcMessage(
                        "cgc: only `QP solver/Stopping criterion = projected' "
                        "(CGC's criterion is the projected gradient)."));
          auto rows = std::make_shared<LinearInequalities>();
          if (problem.constraints)
            problem.constraints->for_each_bound_and_box(
              [&](const auto index, const double lower, const double upper)
              {
                rows->add_lower_bound(index, lower);
                if (upper < std::numeric_limits<double>::infinity())
                  rows->add_upper_bound(index, upper);
              });
          CGCProblem<VectorType> cgc_problem;
          cgc_problem.hessian     = problem.hessian;
          cgc_problem.b           = problem.b;
          cgc_problem.constraints = rows;

          typename CGC<VectorType>::AdditionalData data;
          data.tolerance         = prm.tolerance;
          data.max_iterations    = prm.max_iterations;
          data.stagnation_window = prm.stagnation_window;
          CGC<VectorType>  cgc(data);
          SolverStatistics stats = cgc.solve(cgc_problem, x);
          // CGC's stationarity is its own criterion (||g^P|| for these rows);
          // the other residuals from the separable problem
          const double stationarity = stats.kkt.stationarity;
          stats.kkt                 = compute_kkt_residuals(problem, x);
          stats.kkt.stationarity =
            std::min(stationarity, stats.kkt.stationarity);
          return stats;
        }
      };
    } // namespace


    SolverEntry
    cgc_solver_entry()
    {
      // not chainable: CGC's facet restarts take more products than the
      // MPGP family on the same problem (the report's DUAL method, kept
      // for its tables, not for the fall-back chains)
      return solver_entry<CGCSolver>(
        "cgc",
        AcceptedSets::bounds_and_boxes,
        "the 1996 report's conjugate gradients with projection and facet "
        "restarts (its DUAL method), bound and box constraints only",
        false);
    }
  } // namespace qp
} // namespace dualcontact
