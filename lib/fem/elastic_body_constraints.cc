#include <deal.II/dofs/dof_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <fem/elastic_body.h>

#include <cmath>

// ElasticBody's constraints and the time of its loads (a load step): apart
// from elastic_body.cc, which holds the assembly, to keep files short.

namespace dualcontact
{
  namespace fem
  {
    using namespace dealii;

    template <int dim>
    void
    ElasticBody<dim>::make_constraints()
    {
      constraints_.clear();
      DoFTools::make_hanging_node_constraints(dof_handler_, constraints_);
      // on a distributed mesh every process needs the lines of all dofs:
      // TFETI's multiplier rows and the condensed contact rows are the
      // same everywhere
      if (is_distributed())
        gather_constraint_lines(true);
      // the hanging nodes alone, before the Dirichlet conditions join them
      hanging_node_constraints_.copy_from(constraints_);
      hanging_node_constraints_.close();
      // Conditions are applied in the order given: where two boundaries meet,
      // the first condition on a dof wins (AffineConstraints keeps the first).
      for (const auto &condition : dirichlet_)
        VectorTools::interpolate_boundary_values(*mapping_,
                                                 dof_handler_,
                                                 condition.boundary_id,
                                                 *condition.values,
                                                 constraints_,
                                                 condition.components);
      if (is_distributed())
        gather_constraint_lines(false);
      constraints_.close();
      for (const auto &line : constraints_.get_lines())
        AssertThrow(std::isfinite(line.inhomogeneity),
                    ExcMessage(name_ +
                               ": a prescribed displacement (`set "
                               "Displacement' of a `Dirichlet N') is not "
                               "finite at a boundary node: check its "
                               "expression (a division by zero, the square "
                               "root or logarithm of a negative number, an "
                               "overflow)."));
    }


    template <int dim>
    void
    ElasticBody<dim>::set_load_time(const double time)
    {
      for (auto &condition : dirichlet_)
        condition.values->set_time(time);
      for (auto &condition : tractions_)
        condition.traction->set_time(time);
      if (body_force_)
        body_force_->set_time(time);
      // the prescribed values at the new time; the lines (which dofs, which
      // hanging nodes) are those of setup(), so K is unchanged
      if (dof_handler_.n_dofs() > 0)
        make_constraints();
    }


    template void
    ElasticBody<2>::make_constraints();
    template void
    ElasticBody<3>::make_constraints();
    template void
    ElasticBody<2>::set_load_time(const double);
    template void
    ElasticBody<3>::set_load_time(const double);
  } // namespace fem
} // namespace dualcontact
