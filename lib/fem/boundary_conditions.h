#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/types.h>
#include <deal.II/fe/component_mask.h>

#include <memory>

namespace dualcontact
{
  namespace fem
  {
    /**
     * Prescribed displacement [m] on the boundary faces with id
     * @p boundary_id, for the displacement components selected by
     * @p components.  @p values has dim components (the unselected ones are
     * ignored), each a function of the reference position x (and of the time of
     * a load step, Function::set_time()).
     */
    template <int dim>
    struct DirichletCondition
    {
      dealii::types::boundary_id             boundary_id;
      dealii::ComponentMask                  components;
      std::shared_ptr<dealii::Function<dim>> values;
    };

    /**
     * Surface traction t [N/m^2] (force per unit area of the reference
     * configuration; per unit length and thickness in 2D) on the boundary
     * faces with id @p boundary_id; @p traction has dim components.
     */
    template <int dim>
    struct TractionCondition
    {
      dealii::types::boundary_id             boundary_id;
      std::shared_ptr<dealii::Function<dim>> traction;
    };
  } // namespace fem
} // namespace dualcontact
