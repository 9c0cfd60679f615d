#include <qp/free_set_amg.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_index_access.h>

#include <Epetra_CrsMatrix.h>

#include <string>

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
        , amg(std::make_shared<dealii::TrilinosWrappers::PreconditionAMG>())
    {
      AssertThrow(dealii::Utilities::MPI::job_supports_mpi(),
                  dealii::ExcMessage(
                    "FreeSetAMG: Trilinos' AMG needs MPI to be initialized "
                    "(dealii::Utilities::MPI::MPI_InitFinalize in main)"));
      AssertThrow(A.m() == A.n() && A.m() > 0,
                  dealii::ExcMessage(
                    "FreeSetAMG: the Hessian must be a non-empty square "
                    "matrix"));
      AssertThrow(parameters.keep_fraction >= 0. &&
                    parameters.keep_fraction <= 1.,
                  dealii::ExcMessage("FreeSetAMG: keep fraction " +
                                     std::to_string(parameters.keep_fraction) +
                                     " is not in [0, 1]"));
      double sum = 0.;
      for (unsigned int i = 0; i < A.m(); ++i)
        sum += A.diag_element(i);
      unit = sum > 0. ? sum / A.m() : 1.;
      // serial Trilinos copy of A (MPI_COMM_SELF) with A's whole pattern:
      // entries below the drop tolerance 0 (exact zeros) stay in the
      // pattern as zeros, as in PreconditionAMG::initialize(SparseMatrix)
      restricted.reinit(A, 0.);
      const Epetra_CrsMatrix &epetra = restricted.trilinos_matrix();
      AssertThrow(static_cast<unsigned int>(epetra.NumMyRows()) == A.m(),
                  dealii::ExcMessage(
                    "FreeSetAMG: the Trilinos copy of A is distributed"));
      original.reserve(epetra.NumMyNonzeros());
      column.reserve(epetra.NumMyNonzeros());
      for (int row = 0; row < epetra.NumMyRows(); ++row)
      {
        int     n_entries = 0;
        double *values    = nullptr;
        int    *indices   = nullptr;
        epetra.ExtractMyRowView(row, n_entries, values, indices);
        for (int k = 0; k < n_entries; ++k)
        {
          original.push_back(values[k]);
          column.push_back(
            dealii::TrilinosWrappers::global_column_index(epetra, indices[k]));
        }
      }
    }


    Teuchos::ParameterList
    FreeSetAMG::ml_parameters()
    {
      // deal.II's translation of the settings, with what it does not
      // expose set on the list
      Teuchos::ParameterList list;
      additional_data().set_parameters(list, constant_modes, restricted);
      list.set("aggregation: damping factor", parameters.prolongator_damping);
      return list;
    }


    dealii::TrilinosWrappers::PreconditionAMG::AdditionalData
    FreeSetAMG::additional_data() const
    {
      dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.n_cycles              = parameters.n_cycles;
      data.aggregation_threshold = parameters.aggregation_threshold;
      data.smoother_sweeps       = parameters.smoother_sweeps;
      return data;
    }


    void
    FreeSetAMG::set_entries(const Vec *active_mask)
    {
      const Epetra_CrsMatrix &epetra = restricted.trilinos_matrix();
      std::size_t             entry  = 0;
      for (int row = 0; row < epetra.NumMyRows(); ++row)
      {
        int     n_entries = 0;
        double *values    = nullptr;
        int    *indices   = nullptr;
        // a view: writing through it changes the matrix ML refers to
        epetra.ExtractMyRowView(row, n_entries, values, indices);
        const bool row_active = active_mask && (*active_mask)[row] != 0.;
        for (int k = 0; k < n_entries; ++k, ++entry)
        {
          const unsigned int j = column[entry];
          if (row_active || (active_mask && (*active_mask)[j] != 0.))
            values[k] = (j == static_cast<unsigned int>(row)) ? unit : 0.;
          else
            values[k] = original[entry];
        }
      }
    }


    typename Problem<FreeSetAMG::Vec>::FreeSetPreconditioner
    FreeSetAMG::build(const Vec &active_mask)
    {
      AssertThrow(active_mask.size() == matrix.m(),
                  dealii::ExcMessage("FreeSetAMG: active mask of size " +
                                     std::to_string(active_mask.size()) +
                                     " for a matrix of size " +
                                     std::to_string(matrix.m())));
      const unsigned int n    = matrix.m();
      bool               keep = false;
      if (!computed_mask.empty())
      {
        std::size_t changed = 0;
        for (unsigned int i = 0; i < n; ++i)
          changed += (active_mask[i] != 0.) != computed_mask[i];
        keep = changed <= parameters.keep_fraction * n;
      }
      if (keep)
        ++kept;
      else
      {
        bool any_active = false;
        for (unsigned int i = 0; i < n && !any_active; ++i)
          any_active = active_mask[i] != 0.;
        if (!parameters.reuse_aggregates)
        {
          set_entries(&active_mask);
          amg->initialize(restricted, ml_parameters());
          ++full_setups;
        }
        else if (computed_mask.empty())
        {
          // aggregates of A itself; then, unless every unknown is free, the
          // recompute for this set
          set_entries(nullptr);
          amg->initialize(restricted, ml_parameters());
          ++full_setups;
          if (any_active)
          {
            set_entries(&active_mask);
            amg->reinit();
            ++recomputes;
          }
        }
        else
        {
          set_entries(&active_mask);
          amg->reinit();
          ++recomputes;
        }
        computed_mask.resize(n);
        for (unsigned int i = 0; i < n; ++i)
          computed_mask[i] = active_mask[i] != 0.;
      }
      const std::shared_ptr<dealii::TrilinosWrappers::PreconditionAMG>
        hierarchy = amg;
      return [hierarchy](Vec &dst, const Vec &src)
      { hierarchy->vmult(dst, src); };
    }


    void
    FreeSetAMG::reset()
    {
      computed_mask.clear();
    }


    std::function<typename Problem<FreeSetAMG::Vec>::FreeSetPreconditioner(
      const FreeSetAMG::Vec &)>
    FreeSetAMG::factory()
    {
      return [this](const Vec &mask) { return build(mask); };
    }
  } // namespace qp
} // namespace dualcontact
