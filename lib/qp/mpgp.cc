#include <qp/mpgp.h>
#include <qp/vector_helpers.h>

namespace dualcontact
{
  namespace qp
  {
    template <typename VectorType>
    ActiveSetVariant
    MPGP<VectorType>::variant()
    {
      ActiveSetVariant v;
      v.test = ActiveSetVariant::Test::gamma;
      v.step = ActiveSetVariant::Step::projection;
      return v;
    }


    template <typename VectorType>
    MPGP<VectorType>::MPGP(const SolverParameters &parameters)
        : ActiveSetSolver<VectorType>("mpgp", parameters, variant())
    {
    }


    template class MPGP<dealii::Vector<double>>;
    template class MPGP<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
