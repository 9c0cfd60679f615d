#include <qp/active_set_iteration.h>
#include <qp/active_set_solver.h>

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

namespace dualcontact
{
  namespace qp
  {
    ActiveSetVariant
    ActiveSetVariant::of(const ActiveSetMethod method)
    {
      ActiveSetVariant variant; // gamma test, projection step
      switch (method)
      {
        case ActiveSetMethod::mprgp:
          variant.step                      = Step::proportioning;
          variant.expand_with_free_gradient = true;
          variant.bounds_only               = true;
          break;
        case ActiveSetMethod::mpgp:
          break;
        case ActiveSetMethod::mpgp_bb:
          variant.barzilai_borwein = true;
          break;
        case ActiveSetMethod::mwpgp:
          variant.test = Test::weak_reduced;
          break;
      }
      return variant;
    }


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
    ActiveSetSolver<VectorType>::ActiveSetSolver(
      const SolverParameters &parameters,
      const ActiveSetMethod   method)
        : ActiveSetSolver(active_set_method_names.name(method),
                          parameters,
                          ActiveSetVariant::of(method))
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
