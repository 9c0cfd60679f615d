#include <deal.II/base/exceptions.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <decomposition/interface_schur_complement.h>

#include <algorithm>
#include <limits>

namespace dualcontact
{
  namespace decomposition
  {
    using namespace dealii;

    InterfaceSchurComplement::InterfaceSchurComplement(
      const SparseMatrix<double>           &stiffness,
      const std::vector<unsigned int>      &interface,
      std::unique_ptr<fem::StiffnessSolver> solver,
      const std::string                    &name)
        : stiffness_(stiffness)
        , n_interface_(interface.size())
        , solver_(std::move(solver))
    {
      const unsigned int n = stiffness.m();
      Assert(std::is_sorted(interface.begin(), interface.end()),
             ExcInternalError());
      // interior index of every local dof (invalid on the interface)
      constexpr unsigned int    none = std::numeric_limits<unsigned int>::max();
      std::vector<unsigned int> interior_index(n, none);
      for (unsigned int i = 0, k = 0; i < n; ++i)
      {
        if (k < interface.size() && interface[k] == i)
        {
          ++k;
          continue;
        }
        interior_index[i] = interior_.size();
        interior_.push_back(i);
      }
      AssertThrow(n_interface_ > 0,
                  ExcMessage(name + " has no dof that a gluing, Dirichlet or "
                                    "contact row touches: its interior "
                                    "stiffness is singular, so the Dirichlet "
                                    "preconditioner (`QP solver/"
                                    "Preconditioner = dirichlet') cannot be "
                                    "built; use lumped or none."));
      if (interior_.empty())
        return;

      DynamicSparsityPattern pattern(interior_.size());
      for (unsigned int r = 0; r < interior_.size(); ++r)
        for (auto entry = stiffness.begin(interior_[r]);
             entry != stiffness.end(interior_[r]);
             ++entry)
          if (interior_index[entry->column()] != none)
            pattern.add(r, interior_index[entry->column()]);
      interior_sparsity_.copy_from(pattern);
      interior_stiffness_.reinit(interior_sparsity_);
      for (unsigned int r = 0; r < interior_.size(); ++r)
        for (auto entry = stiffness.begin(interior_[r]);
             entry != stiffness.end(interior_[r]);
             ++entry)
          if (interior_index[entry->column()] != none)
            interior_stiffness_.set(r,
                                    interior_index[entry->column()],
                                    entry->value());
      try
      {
        solver_->initialize(interior_stiffness_);
      }
      catch (const std::exception &error)
      {
        AssertThrow(false,
                    ExcMessage(name +
                               ": the factorization of its interior "
                               "stiffness K_ii (interface clamped) "
                               "for the Dirichlet preconditioner "
                               "(`QP solver/Preconditioner = "
                               "dirichlet') failed: " +
                               std::string(error.what()) +
                               " A subdomain whose interface does not hold "
                               "its rigid motions needs lumped or none."));
      }
      extension_.reinit(n);
      interior_rhs_.reinit(interior_.size());
      interior_solution_.reinit(interior_.size());
    }


    void
    InterfaceSchurComplement::vmult(Vector<double>       &y,
                                    const Vector<double> &v) const
    {
      y.reinit(stiffness_.m());
      if (interior_.empty())
      {
        stiffness_.vmult(y, v);
        return;
      }
      // x = [v_b; 0], K x gives K_ib v_b on the interior
      extension_ = v;
      for (const unsigned int i : interior_)
        extension_(i) = 0.;
      stiffness_.vmult(y, extension_);
      for (unsigned int r = 0; r < interior_.size(); ++r)
        interior_rhs_(r) = y(interior_[r]);
      solver_->solve(interior_solution_, interior_rhs_);
      // the harmonic extension x_i = -K_ii^{-1} K_ib v_b, and S v_b = (K x)_b
      for (unsigned int r = 0; r < interior_.size(); ++r)
        extension_(interior_[r]) = -interior_solution_(r);
      stiffness_.vmult(y, extension_);
      for (const unsigned int i : interior_)
        y(i) = 0.;
    }


    unsigned int
    InterfaceSchurComplement::n_interface_dofs() const
    {
      return n_interface_;
    }


    unsigned int
    InterfaceSchurComplement::n_interior_dofs() const
    {
      return interior_.size();
    }


    const fem::StiffnessSolver &
    InterfaceSchurComplement::solver() const
    {
      return *solver_;
    }
  } // namespace decomposition
} // namespace dualcontact
