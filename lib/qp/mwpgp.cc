#include <qp/mwpgp.h>
#include <qp/vector_helpers.h>

namespace dualcontact
{
  namespace qp
  {
    template <typename VectorType>
    ActiveSetVariant
    MwPGP<VectorType>::variant()
    {
      ActiveSetVariant v;
      v.test = ActiveSetVariant::Test::weak_reduced;
      v.step = ActiveSetVariant::Step::projection;
      return v;
    }


    template <typename VectorType>
    MwPGP<VectorType>::MwPGP(const SolverParameters &parameters)
        : ActiveSetSolver<VectorType>("mwpgp", parameters, variant())
    {
    }


    template class MwPGP<dealii::Vector<double>>;
    template class MwPGP<dealii::TrilinosWrappers::MPI::Vector>;
  } // namespace qp
} // namespace dualcontact
