#include <fem/generalized_inverse.h>

namespace dualcontact
{
  namespace fem
  {
    GeneralizedInverse::GeneralizedInverse(
      std::unique_ptr<StiffnessSolver>                    solver,
      const std::vector<dealii::types::global_dof_index> &fixing_dofs,
      const std::vector<dealii::Vector<double>>          &kernel)
        : solver_(std::move(solver))
        , fixing_dofs_(fixing_dofs)
        , kernel_(kernel)
    {
      AssertThrow(kernel_.empty() || kernel_.size() == fixing_dofs_.size(),
                  dealii::ExcMessage(
                    "GeneralizedInverse: as many kernel vectors as fixing "
                    "dofs are needed."));
    }


    void
    GeneralizedInverse::initialize(const dealii::SparseMatrix<double> &matrix)
    {
      initialize_reduced(matrix, nullptr, nullptr);
    }


    bool
    GeneralizedInverse::offers_schur_factor() const
    {
      return solver_->offers_schur_factor();
    }


    bool
    GeneralizedInverse::is_distributed() const
    {
      return solver_->is_distributed();
    }


    void
    GeneralizedInverse::initialize_with_schur_factor(
      const dealii::SparseMatrix<double>                 &matrix,
      const std::vector<dealii::types::global_dof_index> &dofs,
      SchurFactor                                        &schur)
    {
      std::vector<bool> fixed(matrix.m(), false);
      for (const auto dof : fixing_dofs_)
        fixed[dof] = true;
      std::vector<dealii::types::global_dof_index> kept;
      for (const auto dof : dofs)
        if (!fixed[dof])
          kept.push_back(dof);
      initialize_reduced(matrix, &kept, &schur);
    }


    void
    GeneralizedInverse::initialize_reduced(
      const dealii::SparseMatrix<double>                 &matrix,
      const std::vector<dealii::types::global_dof_index> *schur_dofs,
      SchurFactor                                        *schur)
    {
      if (fixing_dofs_.empty())
      {
        if (schur_dofs != nullptr)
          solver_->initialize_with_schur_factor(matrix, *schur_dofs, *schur);
        else
          solver_->initialize(matrix);
        statistics_ = solver_->statistics();
        return;
      }
      std::vector<bool> fixed(matrix.m(), false);
      for (const auto dof : fixing_dofs_)
        fixed[dof] = true;
      // a copy only while the solver factorizes (the solvers keep their own
      // data): one K_s less per TFETI subdomain for the whole solve
      dealii::SparseMatrix<double> reduced(matrix.get_sparsity_pattern());
      reduced.copy_from(matrix);
      // Decouple the fixing dofs (rows and columns), keeping their diagonal
      // so that the scale of the matrix is unchanged.
      for (unsigned int i = 0; i < reduced.m(); ++i)
        for (auto it = reduced.begin(i); it != reduced.end(i); ++it)
          if ((fixed[i] || fixed[it->column()]) && it->column() != i)
            it->value() = 0.;
      if (schur_dofs != nullptr)
        solver_->initialize_with_schur_factor(reduced, *schur_dofs, *schur);
      else
        solver_->initialize(reduced);
      statistics_ = solver_->statistics();
    }


    void
    GeneralizedInverse::solve(dealii::Vector<double>       &x,
                              const dealii::Vector<double> &b) const
    {
      if (kernel_.empty())
      {
        solve_fixing_dofs(x, b);
        return;
      }
      // K^+ b = (I - R R') K^# (I - R R') b
      range_part_ = b;
      remove_kernel(range_part_);
      solve_fixing_dofs(x, range_part_);
      remove_kernel(x);
    }


    void
    GeneralizedInverse::remove_kernel(dealii::Vector<double> &v) const
    {
      for (const dealii::Vector<double> &r : kernel_)
        v.add(-(r * v), r);
    }


    const std::vector<dealii::Vector<double>> &
    GeneralizedInverse::kernel() const
    {
      return kernel_;
    }


    void
    GeneralizedInverse::solve_fixing_dofs(dealii::Vector<double>       &x,
                                          const dealii::Vector<double> &b) const
    {
      if (fixing_dofs_.empty())
        solver_->solve(x, b);
      else
      {
        rhs_ = b;
        for (const auto dof : fixing_dofs_)
          rhs_(dof) = 0.;
        solver_->solve(x, rhs_);
        for (const auto dof : fixing_dofs_)
          x(dof) = 0.;
      }
      const double setup     = statistics_.setup_time;
      statistics_            = solver_->statistics();
      statistics_.setup_time = setup;
    }


    std::string
    GeneralizedInverse::name() const
    {
      return solver_->name() +
             (kernel_.empty() ? " (generalized inverse, " :
                                " (pseudoinverse, ") +
             std::to_string(fixing_dofs_.size()) + " fixing dofs)";
    }
  } // namespace fem
} // namespace dualcontact
