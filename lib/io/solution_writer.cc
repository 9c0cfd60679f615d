#include <deal.II/base/data_out_base.h>
#include <deal.II/numerics/data_out.h>

#include <io/contact_surface_writer.h>
#include <io/elasticity_postprocessor.h>
#include <io/solution_writer.h>

#include <memory>
#include <utility>

namespace dualcontact
{
  namespace io
  {
    template <int dim>
    void
    write_solution(
      OutputFolder                                              &folder,
      const std::vector<std::unique_ptr<fem::ElasticBody<dim>>> &bodies,
      const std::vector<dealii::Vector<double>>                 &displacements,
      const std::vector<std::string> &additional_parts)
    {
      std::vector<std::string> pieces;
      // kept for write_pvtu_record, which needs the field names
      // (postprocessor first: the DataOut refers to it and goes first)
      std::unique_ptr<ElasticityPostprocessor<dim>> first_postprocessor;
      std::unique_ptr<dealii::DataOut<dim>>         first_data_out;
      for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const fem::ElasticBody<dim> &body = *bodies[b];
        auto                         postprocessor =
          std::make_unique<ElasticityPostprocessor<dim>>(body, b + 1);
        auto data_out = std::make_unique<dealii::DataOut<dim>>();
        data_out->attach_dof_handler(body.dof_handler());
        data_out->add_data_vector(
          displacements[b],
          std::vector<std::string>(dim, "displacement_m"),
          dealii::DataOut<dim>::type_dof_data,
          std::vector<
            dealii::DataComponentInterpretation::DataComponentInterpretation>(
            dim,
            dealii::DataComponentInterpretation::component_is_part_of_vector));
        data_out->add_data_vector(displacements[b], *postprocessor);
        data_out->build_patches(body.mapping(),
                                body.fe().degree,
                                dealii::DataOut<dim>::curved_inner_cells);
        const std::string name = "body_" + std::to_string(b + 1) + ".vtu";
        folder.write(name,
                     [&data_out](std::ostream &out)
                     { data_out->write_vtu(out); });
        pieces.push_back(name);
        if (b == 0)
        {
          first_data_out      = std::move(data_out);
          first_postprocessor = std::move(postprocessor);
        }
      }
      folder.write("solution.pvtu",
                   [&](std::ostream &out)
                   { first_data_out->write_pvtu_record(out, pieces); });
      std::vector<std::pair<double, std::string>> parts{
        {0., std::string("solution.pvtu")}};
      for (const auto &part : additional_parts)
        parts.emplace_back(0., part);
      folder.write("solution.pvd",
                   [&parts](std::ostream &out) { write_pvd(out, parts); });
    }


    template void
    write_solution<2>(OutputFolder &,
                      const std::vector<std::unique_ptr<fem::ElasticBody<2>>> &,
                      const std::vector<dealii::Vector<double>> &,
                      const std::vector<std::string> &);
    template void
    write_solution<3>(OutputFolder &,
                      const std::vector<std::unique_ptr<fem::ElasticBody<3>>> &,
                      const std::vector<dealii::Vector<double>> &,
                      const std::vector<std::string> &);
  } // namespace io
} // namespace dualcontact
