/**
 * @file solver_factory.h
 * Creation of a QP solver by name (from SolverRegistry), so that the driver,
 * qpsolve and fclibsolve choose the algorithm from the .prm / command line
 * without knowing the classes, and make_solver(), the one place that decides
 * between the fall-back chain, SMALSE-M and a plain solver.
 */
#ifndef dualcontact_qp_solver_factory_h
#define dualcontact_qp_solver_factory_h

#include <qp/problem.h>
#include <qp/smalse_m.h>
#include <qp/solver_base.h>

#include <memory>
#include <string>

namespace dualcontact
{
  namespace qp
  {
    /// All registered solver names, separated by '|' (the pattern of
    /// `Solver`), in registration order.
    std::string
    solver_names();

    /**
     * The solver called @p name (one of solver_names()) with
     * @p parameters; throws ExcMessage listing the valid names otherwise.
     */
    template <typename VectorType>
    std::unique_ptr<SolverBase<VectorType>>
    create(const std::string &name, const SolverParameters &parameters);

    /// create(parameters.solver, parameters)
    template <typename VectorType>
    std::unique_ptr<SolverBase<VectorType>>
    create(const SolverParameters &parameters);

    /**
     * The solver a run uses for a problem with (@p with_equality) or without
     * equality constraints: `auto` is the SolverChain (which wraps SMALSE-M
     * around each of its solvers where needed); otherwise SMALSE-M around
     * the named solver with equality constraints, the named solver without.
     * SolverBase::equality_residual() of the result gives ||Bx - c||.
     */
    template <typename VectorType>
    std::unique_ptr<SolverBase<VectorType>>
    make_solver(const SolverParameters  &parameters,
                const SMALSEMParameters &smalse_parameters,
                bool                     with_equality);

    /// make_solver() for @p problem (with equality if problem.equality).
    template <typename VectorType>
    std::unique_ptr<SolverBase<VectorType>>
    make_solver(const SolverParameters    &parameters,
                const SMALSEMParameters   &smalse_parameters,
                const Problem<VectorType> &problem);
  } // namespace qp
} // namespace dualcontact

#endif
