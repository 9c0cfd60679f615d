#include <qp/mprgp.h>
#include <qp/vector_helpers.h>

namespace dualcontact
{
  namespace qp
  {
    template <typename VectorType>
    ActiveSetVariant
    MPRGP<VectorType>::variant()
    {
      ActiveSetVariant v;
      v.test                      = ActiveSetVariant::Test::gamma;
      v.step                      = ActiveSetVariant::Step::proportioning;
      v.expand_with_free_gradient = true;
      v.bounds_only               = true;
      return v;
    }


    template <typename VectorType>
    MPRGP<VectorType>::MPRGP(const SolverParameters &parameters)
        : ActiveSetSolver<VectorType>("mprgp", parameters, variant())
    {
    }


    template class MPRGP<dealii::Vector<double>>;
    template class MPRGP<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
