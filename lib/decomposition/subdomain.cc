#include <deal.II/base/exceptions.h>

#include <decomposition/subdomain.h>
#include <fem/generalized_inverse.h>

#include <algorithm>

namespace dualcontact
{
  namespace decomposition
  {
    using namespace dealii;

    template <int dim>
    Subdomain<dim>::Subdomain(const fem::ElasticBody<dim>     &body,
                              const unsigned int               body_index,
                              const std::vector<CellIterator> &cells,
                              const std::vector<Point<dim>>   &support_points,
                              const std::vector<unsigned int> &components,
                              const std::string               &name)
        : name_(name)
        , body_object_(&body)
        , body_(body_index)
        , cells_(cells)
        , n_cells_(cells.size())
    {
      AssertThrow(!cells.empty(), ExcMessage(name + " has no cells."));
      std::vector<types::global_dof_index> cell_dofs(
        body.fe().n_dofs_per_cell());
      for (const auto &cell : cells)
      {
        cell->get_dof_indices(cell_dofs);
        dofs_.insert(dofs_.end(), cell_dofs.begin(), cell_dofs.end());
      }
      std::sort(dofs_.begin(), dofs_.end());
      dofs_.erase(std::unique(dofs_.begin(), dofs_.end()), dofs_.end());
      body.assemble_cells(cells, dofs_, sparsity_, stiffness_, load_);
      modes_ = std::make_unique<fem::RigidBodyModes<dim>>(support_points,
                                                          components,
                                                          dofs_,
                                                          name);
      AssertThrow(modes_->n_modes() == dim * (dim + 1) / 2, ExcInternalError());
    }


    template <int dim>
    void
    Subdomain<dim>::assemble_load()
    {
      // assemble_cells() integrates K_s too (into a matrix let go here):
      // the body offers no load-only integral of a set of cells yet
      dealii::SparsityPattern      sparsity;
      dealii::SparseMatrix<double> matrix;
      body_object_->assemble_cells(cells_, dofs_, sparsity, matrix, load_);
    }


    template <int dim>
    void
    Subdomain<dim>::factorize(std::unique_ptr<fem::StiffnessSolver> solver)
    {
      std::vector<types::global_dof_index> fixing = modes_->fixing_dofs();
      solver_ = std::make_unique<fem::GeneralizedInverse>(std::move(solver),
                                                          fixing,
                                                          modes_->modes());
      solver_->initialize(stiffness_);
    }


    template <int dim>
    void
    Subdomain<dim>::release_stiffness_matrix()
    {
      stiffness_.clear();
      sparsity_.reinit(0, 0, 0);
    }


    template <int dim>
    void
    Subdomain<dim>::apply_pseudoinverse(Vector<double>       &x,
                                        const Vector<double> &b) const
    {
      Assert(solver_, ExcMessage("Subdomain: factorize() first."));
      solver_->solve(x, b);
    }


    template <int dim>
    unsigned int
    Subdomain<dim>::local_index(const types::global_dof_index dof) const
    {
      const auto it = std::lower_bound(dofs_.begin(), dofs_.end(), dof);
      Assert(it != dofs_.end() && *it == dof, ExcInternalError());
      return it - dofs_.begin();
    }


    template <int dim>
    const std::string &
    Subdomain<dim>::name() const
    {
      return name_;
    }


    template <int dim>
    unsigned int
    Subdomain<dim>::body() const
    {
      return body_;
    }


    template <int dim>
    unsigned int
    Subdomain<dim>::n_cells() const
    {
      return n_cells_;
    }


    template <int dim>
    unsigned int
    Subdomain<dim>::n_dofs() const
    {
      return dofs_.size();
    }


    template <int dim>
    const std::vector<types::global_dof_index> &
    Subdomain<dim>::dofs() const
    {
      return dofs_;
    }


    template <int dim>
    const Vector<double> &
    Subdomain<dim>::load() const
    {
      return load_;
    }


    template <int dim>
    const SparseMatrix<double> &
    Subdomain<dim>::stiffness_matrix() const
    {
      Assert(stiffness_.m() == dofs_.size(),
             ExcMessage("Subdomain: K_s was released."));
      return stiffness_;
    }


    template <int dim>
    const std::vector<Vector<double>> &
    Subdomain<dim>::modes() const
    {
      return modes_->modes();
    }


    template <int dim>
    const fem::StiffnessSolver &
    Subdomain<dim>::solver() const
    {
      Assert(solver_, ExcMessage("Subdomain: factorize() first."));
      return *solver_;
    }


    template class Subdomain<2>;
    template class Subdomain<3>;
  } // namespace decomposition
} // namespace dualcontact
