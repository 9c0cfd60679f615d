/**
 * @file solver_factory.h
 * Creation of a QP solver by name, so that the driver and qpsolve choose
 * the algorithm from the .prm / command line without knowing the classes.
 */
#ifndef dualcontact_qp_solver_factory_h
#define dualcontact_qp_solver_factory_h

#include <qp/solver_base.h>

#include <memory>
#include <string>

namespace dualcontact
{
  namespace qp
  {
    /// All solver names, separated by '|' (the pattern of `Solver`).
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
  } // namespace qp
} // namespace dualcontact

#endif
