#include <deal.II/base/exceptions.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <decomposition/multiplier_scaling.h>
#include <fem/cholmod_solver.h>

#include <string>

namespace dualcontact
{
  namespace decomposition
  {
    MultiplierScaling::MultiplierScaling(const unsigned int         n_rows,
                                         const std::vector<double> &products)
    {
      const auto index = [](const double x)
      { return static_cast<unsigned int>(x); };
      dealii::DynamicSparsityPattern pattern(n_rows);
      for (unsigned int r = 0; r < n_rows; ++r)
        pattern.add(r, r);
      for (std::size_t k = 0; k < products.size(); k += 3)
        pattern.add(index(products[k]), index(products[k + 1]));
      sparsity.copy_from(pattern);
      bbt.reinit(sparsity);
      for (std::size_t k = 0; k < products.size(); k += 3)
        bbt.add(index(products[k]), index(products[k + 1]), products[k + 2]);
      for (unsigned int r = 0; r < n_rows; ++r)
        if (bbt.diag_element(r) == 0.)
          bbt.diag_element(r) = 1.;
      factor = std::make_unique<fem::CholmodSolver>();
      try
      {
        factor->initialize(bbt);
      }
      catch (const std::exception &error)
      {
        AssertThrow(false,
                    dealii::ExcMessage(
                      "TFETI: B B', the scaling of the lumped and the "
                      "Dirichlet preconditioner, is singular (the rows of B "
                      "are linearly dependent: contact rows of two pairs on "
                      "the same dofs?); use `QP solver/Preconditioner = "
                      "none'. " +
                      std::string(error.what())));
      }
    }


    void
    MultiplierScaling::apply(dealii::Vector<double> &v) const
    {
      scaled.reinit(v.size(), true);
      factor->solve(scaled, v);
      v.swap(scaled);
    }
  } // namespace decomposition
} // namespace dualcontact
