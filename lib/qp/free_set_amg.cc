#include <qp/free_set_amg.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_precondition.h>

#include <memory>

namespace dualcontact
{
  namespace qp
  {
    FreeSetAMG::FreeSetAMG(const dealii::SparseMatrix<double> &A)
        : FreeSetAMG(A, Parameters())
    {
    }


    FreeSetAMG::FreeSetAMG(const dealii::SparseMatrix<double> &A,
                           const Parameters                   &parameters)
        : matrix(A)
        , parameters(parameters)
    {
      AssertThrow(dealii::Utilities::MPI::job_supports_mpi(),
                  dealii::ExcMessage(
                    "FreeSetAMG: Trilinos' AMG needs MPI to be initialized "
                    "(dealii::Utilities::MPI::MPI_InitFinalize in main)"));
      AssertThrow(A.m() == A.n() && A.m() > 0,
                  dealii::ExcMessage(
                    "FreeSetAMG: the Hessian must be a non-empty square "
                    "matrix"));
      double sum = 0.;
      for (unsigned int i = 0; i < A.m(); ++i)
        sum += A.diag_element(i);
      unit = sum > 0. ? sum / A.m() : 1.;
      restricted.reinit(A.get_sparsity_pattern());
    }


    typename Problem<FreeSetAMG::Vec>::FreeSetPreconditioner
    FreeSetAMG::build(const Vec &active_mask)
    {
      AssertThrow(active_mask.size() == matrix.m(),
                  dealii::ExcMessage("FreeSetAMG: active mask of size " +
                                     std::to_string(active_mask.size()) +
                                     " for a matrix of size " +
                                     std::to_string(matrix.m())));
      restricted.copy_from(matrix);
      for (unsigned int i = 0; i < restricted.m(); ++i)
      {
        const bool row_active = active_mask[i] != 0.;
        for (auto entry = restricted.begin(i); entry != restricted.end(i);
             ++entry)
        {
          const unsigned int j = entry->column();
          if (row_active || active_mask[j] != 0.)
            entry->value() = (i == j) ? unit : 0.;
        }
      }
      dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.n_cycles              = parameters.n_cycles;
      data.aggregation_threshold = parameters.aggregation_threshold;
      data.smoother_sweeps       = parameters.smoother_sweeps;
      auto amg = std::make_shared<dealii::TrilinosWrappers::PreconditionAMG>();
      // drop the zeroed couplings when copying into Trilinos' matrix
      amg->initialize(restricted, data, 0.);
      return [amg](Vec &dst, const Vec &src) { amg->vmult(dst, src); };
    }


    std::function<typename Problem<FreeSetAMG::Vec>::FreeSetPreconditioner(
      const FreeSetAMG::Vec &)>
    FreeSetAMG::factory()
    {
      return [this](const Vec &mask) { return build(mask); };
    }
  } // namespace qp
} // namespace dualcontact
