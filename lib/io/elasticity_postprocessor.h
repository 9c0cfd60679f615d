#pragma once

#include <deal.II/numerics/data_postprocessor.h>

#include <fem/elastic_body.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    /**
     * Derived fields of a displacement solution for DataOut, at each output
     * point (names carry the unit after the last underscore; 2D: plane
     * strain):
     *  - `stress_Pa': Cauchy stress tensor sigma = C : eps [Pa] (dim x dim;
     *    ParaView shows 2D tensors padded to 3 x 3, without sigma_zz),
     *  - `von_mises_stress_Pa': von Mises stress of the full 3D stress state
     *    (2D: with sigma_zz = nu (sigma_xx + sigma_yy)) [Pa],
     *  - `strain': small strain tensor eps = sym grad u [-],
     *  - `material_id', `body_id': of the cell (constant per cell).
     * The material of a cell comes from its material id.
     */
    template <int dim>
    class ElasticityPostprocessor : public dealii::DataPostprocessor<dim>
    {
    public:
      ElasticityPostprocessor(const fem::ElasticBody<dim> &body,
                              const unsigned int           body_id);

      void
      evaluate_vector_field(
        const dealii::DataPostprocessorInputs::Vector<dim> &inputs,
        std::vector<dealii::Vector<double>>                &computed_quantities)
        const override;

      std::vector<std::string>
      get_names() const override;

      std::vector<
        dealii::DataComponentInterpretation::DataComponentInterpretation>
      get_data_component_interpretation() const override;

      dealii::UpdateFlags
      get_needed_update_flags() const override;

    private:
      const fem::ElasticBody<dim> &body_;
      const unsigned int           body_id_;
    };
  } // namespace io
} // namespace dualcontact
