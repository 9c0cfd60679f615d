#include <qp/mpgp_bb.h>
#include <qp/vector_helpers.h>

namespace dualcontact
{
  namespace qp
  {
    template <typename VectorType>
    ActiveSetVariant
    MPGPBB<VectorType>::variant()
    {
      ActiveSetVariant v;
      v.test             = ActiveSetVariant::Test::gamma;
      v.step             = ActiveSetVariant::Step::projection;
      v.barzilai_borwein = true;
      return v;
    }


    template <typename VectorType>
    MPGPBB<VectorType>::MPGPBB(const SolverParameters &parameters)
        : ActiveSetSolver<VectorType>("mpgp-bb", parameters, variant())
    {
    }


    template class MPGPBB<dealii::Vector<double>>;
    template class MPGPBB<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
