#include <deal.II/base/symmetric_tensor.h>

#include <io/elasticity_postprocessor.h>

namespace dualcontact
{
  namespace io
  {
    template <int dim>
    ElasticityPostprocessor<dim>::ElasticityPostprocessor(
      const fem::ElasticBody<dim> &body,
      const unsigned int           body_id)
        : body_(body)
        , body_id_(body_id)
    {
    }


    template <int dim>
    void
    ElasticityPostprocessor<dim>::evaluate_vector_field(
      const dealii::DataPostprocessorInputs::Vector<dim> &inputs,
      std::vector<dealii::Vector<double>> &computed_quantities) const
    {
      const auto                    cell = inputs.template get_cell<dim>();
      const fem::IsotropicMaterial &material =
        body_.material(cell->material_id());
      const unsigned int n_tensor = dim * dim;
      for (unsigned int q = 0; q < inputs.solution_gradients.size(); ++q)
      {
        dealii::Tensor<2, dim> gradient;
        for (unsigned int i = 0; i < dim; ++i)
          gradient[i] = inputs.solution_gradients[q][i];
        const dealii::SymmetricTensor<2, dim> strain = symmetrize(gradient);
        const dealii::SymmetricTensor<2, dim> stress =
          material.stress<dim>(strain);
        dealii::Vector<double> &out = computed_quantities[q];
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
          {
            out[i * dim + j]                = stress[i][j];
            out[n_tensor + 1 + i * dim + j] = strain[i][j];
          }
        out[n_tensor]         = material.von_mises_stress<dim>(stress);
        out[2 * n_tensor + 1] = cell->material_id();
        out[2 * n_tensor + 2] = body_id_;
      }
    }


    template <int dim>
    std::vector<std::string>
    ElasticityPostprocessor<dim>::get_names() const
    {
      std::vector<std::string> names(dim * dim, "stress_Pa");
      names.emplace_back("von_mises_stress_Pa");
      names.insert(names.end(), dim * dim, "strain");
      names.emplace_back("material_id");
      names.emplace_back("body_id");
      return names;
    }


    template <int dim>
    std::vector<
      dealii::DataComponentInterpretation::DataComponentInterpretation>
    ElasticityPostprocessor<dim>::get_data_component_interpretation() const
    {
      using namespace dealii::DataComponentInterpretation;
      std::vector<DataComponentInterpretation> interpretation(
        dim * dim, component_is_part_of_tensor);
      interpretation.push_back(component_is_scalar);
      interpretation.insert(interpretation.end(),
                            dim * dim,
                            component_is_part_of_tensor);
      interpretation.push_back(component_is_scalar);
      interpretation.push_back(component_is_scalar);
      return interpretation;
    }


    template <int dim>
    dealii::UpdateFlags
    ElasticityPostprocessor<dim>::get_needed_update_flags() const
    {
      return dealii::update_gradients;
    }


    template class ElasticityPostprocessor<2>;
    template class ElasticityPostprocessor<3>;
  } // namespace io
} // namespace dualcontact
