#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria_base.h>
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
      const std::vector<std::string>              &additional_parts,
      const std::string                           &suffix,
      const double                                 time,
      std::vector<std::pair<double, std::string>> *series)
    {
      // DataOut writes the locally owned cells: on a parallel
      // triangulation one piece per process and body
      unsigned int n_ranks = 1, rank = 0;
      if (!bodies.empty())
        if (const auto *parallel =
              dynamic_cast<const dealii::parallel::TriangulationBase<dim> *>(
                &bodies.front()->triangulation()))
        {
          n_ranks = dealii::Utilities::MPI::n_mpi_processes(
            parallel->get_communicator());
          rank = dealii::Utilities::MPI::this_mpi_process(
            parallel->get_communicator());
        }
      const auto piece_name =
        [n_ranks, &suffix](const unsigned int b, const unsigned int r)
      {
        return "body_" + std::to_string(b + 1) + suffix +
               (n_ranks > 1 ? "_rank_" + std::to_string(r) : "") + ".vtu";
      };
      std::vector<std::string> pieces;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        for (unsigned int r = 0; r < n_ranks; ++r)
          pieces.push_back(piece_name(b, r));
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
                                body.cell_family().output_subdivisions(
                                  body.fe().degree),
                                dealii::DataOut<dim>::curved_inner_cells);
        // zlib's fastest level: with deal.II's default (best compression)
        // the Output phase of the 128,000-cell brick took 36 s, with this
        // 10.7 s on a busier machine, for a body_1.vtu 4 % larger (71.9
        // against 68.9 MB; issue 17, doc/benchmarks/tfeti.md)
        dealii::DataOutBase::VtkFlags flags;
        flags.compression_level = dealii::DataOutBase::VtkFlags::best_speed;
        data_out->set_flags(flags);
        folder.write(piece_name(b, rank),
                     [&data_out](std::ostream &out)
                     { data_out->write_vtu(out); });
        if (b == 0)
        {
          first_data_out      = std::move(data_out);
          first_postprocessor = std::move(postprocessor);
        }
      }
      if (rank != 0)
        return;
      // the other processes' pieces, so that a later run on fewer
      // processes into this folder removes them (OutputFolder::commit)
      for (unsigned int b = 0; b < bodies.size(); ++b)
        for (unsigned int r = 1; r < n_ranks; ++r)
          folder.list_file_of_other_process(piece_name(b, r));
      const std::string record = "solution" + suffix + ".pvtu";
      folder.write(record,
                   [&](std::ostream &out)
                   { first_data_out->write_pvtu_record(out, pieces); });
      std::vector<std::pair<double, std::string>> parts{{time, record}};
      for (const auto &part : additional_parts)
        parts.emplace_back(time, part);
      if (series != nullptr)
      {
        series->insert(series->end(), parts.begin(), parts.end());
        return;
      }
      folder.write("solution.pvd",
                   [&parts](std::ostream &out) { write_pvd(out, parts); });
    }


    template void
    write_solution<2>(OutputFolder &,
                      const std::vector<std::unique_ptr<fem::ElasticBody<2>>> &,
                      const std::vector<dealii::Vector<double>> &,
                      const std::vector<std::string> &,
                      const std::string &,
                      const double,
                      std::vector<std::pair<double, std::string>> *);
    template void
    write_solution<3>(OutputFolder &,
                      const std::vector<std::unique_ptr<fem::ElasticBody<3>>> &,
                      const std::vector<dealii::Vector<double>> &,
                      const std::vector<std::string> &,
                      const std::string &,
                      const double,
                      std::vector<std::pair<double, std::string>> *);
  } // namespace io
} // namespace dualcontact
