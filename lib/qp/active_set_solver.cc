#include <qp/active_set_iteration.h>
#include <qp/active_set_solver.h>

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

namespace dualcontact
{
  namespace qp
  {
    template <typename VectorType>
    ActiveSetSolver<VectorType>::ActiveSetSolver(
      const std::string      &name,
      const SolverParameters &parameters,
      const ActiveSetVariant &variant)
        : SolverBase<VectorType>(name, parameters)
        , variant(variant)
    {
    }


    template <typename VectorType>
    SolverStatistics
    ActiveSetSolver<VectorType>::solve(const Problem<VectorType> &problem,
                                       VectorType                &x)
    {
      ActiveSetIteration<VectorType> iteration(*this, problem, x);
      return iteration.run();
    }


    template class ActiveSetSolver<dealii::Vector<double>>;
    template class ActiveSetSolver<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
