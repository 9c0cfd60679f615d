#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <driver/results_report.h>
#include <fclib/fclib_file.h>
#include <fclib/scene_export.h>
#include <io/contact_surface_writer.h>
#include <io/parameter_file.h>
#include <io/solution_writer.h>
#include <util/blas_kernels.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace dualcontact
{
  namespace driver
  {
    namespace
    {
      std::string
      format_number(const double value)
      {
        std::ostringstream text;
        text << std::setprecision(12) << std::scientific << value;
        return text.str();
      }

      /**
       * Components below 1e-10 * @p scale are round-off of a zero (e.g. the
       * reaction along an unloaded direction): print them as 0 so that the
       * reference comparison does not depend on round-off.
       */
      template <int dim>
      std::string
      format_vector(const dealii::Tensor<1, dim> &vector, const double scale)
      {
        std::string text;
        for (unsigned int d = 0; d < dim; ++d)
          text +=
            (d == 0 ? "" : ", ") +
            format_number(std::abs(vector[d]) < 1e-10 * scale ? 0. : vector[d]);
        return text;
      }

      /**
       * A body's force imbalance below this is round-off (the solves leave
       * 1e-13 .. 1e-10 of the forces): printed as 0 so that the reference
       * comparison does not depend on it (statistics.json has the value).
       */
      constexpr double force_imbalance_round_off = 1e-10;

      template <int dim>
      std::vector<double>
      to_vector(const dealii::Tensor<1, dim> &tensor)
      {
        std::vector<double> values(dim);
        for (unsigned int d = 0; d < dim; ++d)
          values[d] = tensor[d];
        return values;
      }
    } // namespace


    template <int dim>
    ResultsReport<dim>::ResultsReport(const Scene<dim>        &scene,
                                      const ContactStage<dim> *contact,
                                      const std::string       &parameter_file)
        : scene_(scene)
        , contact_(contact)
        , parameter_file_(parameter_file)
    {
    }


    template <int dim>
    std::string
    ResultsReport<dim>::results_text() const
    {
      std::ostringstream out;
      out << "# dualcontact results, SI units"
          << (dim == 2 ? " (2D plane strain: per metre of thickness)" : "")
          << "\n";
      out << "dimension = " << dim << "\n";
      out << "n_bodies = " << scene_.n_bodies() << "\n";
      double total_energy = 0, total_work = 0;
      for (unsigned int b = 0; b < scene_.n_bodies(); ++b)
      {
        const auto       &r      = scene_.results()[b];
        const std::string prefix = "body_" + std::to_string(b + 1) + ".";
        // the size of the forces in this body, to recognize round-off
        // zeros: the largest resultant, or energy / displacement when
        // nothing is loaded (prescribed displacements only)
        double force_scale =
          std::max(r.applied_force.norm(), r.contact_force.norm());
        for (const auto &[id, force] : r.reaction_forces)
          force_scale = std::max(force_scale, force.norm());
        if (r.max_displacement > 0)
          force_scale =
            std::max(force_scale, r.strain_energy / r.max_displacement);
        out << prefix << "n_cells = "
            << scene_.body(b).triangulation().n_global_active_cells() << "\n";
        out << prefix << "n_dofs = " << scene_.body(b).n_dofs() << "\n";
        out << prefix << "strain_energy = " << format_number(r.strain_energy)
            << "\n";
        out << prefix << "external_work = " << format_number(r.external_work)
            << "\n";
        out << prefix
            << "max_displacement = " << format_number(r.max_displacement)
            << "\n";
        out << prefix << "applied_force = "
            << format_vector<dim>(r.applied_force, force_scale) << "\n";
        for (const auto &[id, force] : r.reaction_forces)
          out << prefix << "reaction_force.boundary_" << id << " = "
              << format_vector<dim>(force, force_scale) << "\n";
        if (contact_ != nullptr)
          out << prefix << "contact_force = "
              << format_vector<dim>(r.contact_force, force_scale) << "\n";
        out << prefix << "force_imbalance = "
            << format_number(r.force_imbalance < force_imbalance_round_off ?
                               0. :
                               r.force_imbalance)
            << "\n";
        // per traction condition: the resultant on the exact surface and
        // the one the load vector carries (ElasticBody::TractionResultant)
        for (unsigned int t = 0; t < r.traction_resultants.size(); ++t)
        {
          const auto       &resultant = r.traction_resultants[t];
          const std::string traction =
            prefix + "traction_" + std::to_string(t + 1) + ".";
          out << traction << "boundary_id = " << resultant.boundary_id << "\n";
          out << traction << "nominal_force = "
              << format_vector<dim>(resultant.nominal, force_scale) << "\n";
          out << traction << "applied_force = "
              << format_vector<dim>(resultant.applied, force_scale) << "\n";
          out << traction << "relative_difference = "
              << format_number(resultant.relative_difference() < 1e-12 ?
                                 0. :
                                 resultant.relative_difference())
              << "\n";
        }
        total_energy += r.strain_energy;
        total_work += r.external_work;
      }
      out << "total.strain_energy = " << format_number(total_energy) << "\n";
      out << "total.external_work = " << format_number(total_work) << "\n";
      if (contact_ != nullptr)
      {
        out << "contact.converged = " << (contact_->result().converged ? 1 : 0)
            << "\n";
        out << "contact.n_qp_solves = "
            << contact_->result().qp_statistics.size() << "\n";
        out << "contact.n_multipliers = " << contact_->dual().n_multipliers()
            << "\n";
        if (const auto *tfeti = contact_->tfeti())
          out << "contact.n_subdomains = " << tfeti->n_subdomains() << "\n";
      }
      const std::vector<typename ContactStage<dim>::PairResults> pair_results =
        contact_ != nullptr ?
          contact_->pair_results() :
          std::vector<typename ContactStage<dim>::PairResults>();
      for (unsigned int p = 0; p < pair_results.size(); ++p)
      {
        const auto       &r      = pair_results[p];
        const std::string prefix = "pair_" + std::to_string(p + 1) + ".";
        const double      scale =
          std::max(r.normal_force, r.tangential_force.norm());
        out << prefix << "n_nodes = " << r.n_nodes << "\n";
        out << prefix << "n_separated = " << r.n_separated << "\n";
        out << prefix << "n_stick = " << r.n_stick << "\n";
        out << prefix << "n_slip = " << r.n_slip << "\n";
        out << prefix << "n_contact = " << r.n_contact << "\n";
        out << prefix << "area = " << format_number(r.area) << "\n";
        out << prefix << "min_initial_gap = " << format_number(r.min_gap)
            << "\n";
        out << prefix << "max_initial_gap = " << format_number(r.max_gap)
            << "\n";
        out << prefix << "normal_force = " << format_number(r.normal_force)
            << "\n";
        out << prefix << "tangential_force = "
            << format_vector<dim>(r.tangential_force, scale) << "\n";
        out << prefix
            << "contact_force = " << format_vector<dim>(r.contact_force, scale)
            << "\n";
        out << prefix << "max_pressure = " << format_number(r.max_pressure)
            << "\n";
        out << prefix << (dim == 2 ? "contact_length = " : "contact_area = ")
            << format_number(r.contact_measure) << "\n";
      }
      if (with_dissipation_ && contact_ != nullptr)
      {
        // a load history: the work of friction on the slip increments
        double total = 0;
        for (unsigned int p = 0; p < contact_->dissipated_energy().size(); ++p)
        {
          out << "pair_" << p + 1 << ".dissipated_energy = "
              << format_number(contact_->dissipated_energy()[p]) << "\n";
          total += contact_->dissipated_energy()[p];
        }
        out << "total.dissipated_energy = " << format_number(total) << "\n";
      }
      if (cycles_ != nullptr && !cycles_->empty())
      {
        out << "refinement.n_solves = " << cycles_->size() << "\n";
        for (const auto &c : *cycles_)
        {
          const std::string prefix =
            "refinement.cycle_" + std::to_string(c.cycle) + ".";
          unsigned int n_dofs = 0, n_cells = 0;
          for (unsigned int b = 0; b < c.n_dofs.size(); ++b)
          {
            n_dofs += c.n_dofs[b];
            n_cells += c.n_cells[b];
          }
          out << prefix << "n_cells = " << n_cells << "\n";
          out << prefix << "n_dofs = " << n_dofs << "\n";
          out << prefix << "n_contact_nodes = " << c.n_contact_nodes << "\n";
          out << prefix << "n_in_contact = " << c.n_in_contact << "\n";
          for (unsigned int p = 0; p < c.pair_nodes.size(); ++p)
          {
            const std::string pair = prefix + "pair_" + std::to_string(p + 1);
            out << pair
                << ".normal_force = " << format_number(c.pair_normal_force[p])
                << "\n";
            out << pair
                << ".max_pressure = " << format_number(c.pair_max_pressure[p])
                << "\n";
          }
          if (&c != &cycles_->back())
            out << prefix << "n_marked_cells = " << c.n_marked_cells << "\n";
        }
      }
      return out.str();
    }


    template <int dim>
    std::string
    ResultsReport<dim>::statistics_json(const dealii::TimerOutput &timer) const
    {
      nlohmann::json json;
      json["program"]        = "dualcontact";
      json["version"]        = DUALCONTACT_VERSION;
      json["parameter_file"] = parameter_file_;
      json["dimension"]      = dim;
      json["fe_degree"]      = scene_.fe_degree();
      json["mpi_processes"] =
        dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
      // which BLAS kernels and threads ran (util/blas_kernels.h): they
      // decide the factorization's and the dense dual operator's speed
      json["blas"] = {{"core", util::blas_core_name()},
                      {"choice", util::blas_kernel_report()},
                      {"threads", util::blas_threads()}};

      nlohmann::json timing;
      for (const auto &[section, seconds] :
           timer.get_summary_data(dealii::TimerOutput::total_wall_time))
        timing[section] = seconds;
      json["wall_time_s"] = timing;

      nlohmann::json bodies = nlohmann::json::array();
      for (unsigned int b = 0; b < scene_.n_bodies(); ++b)
      {
        const auto    &r          = scene_.results()[b];
        const auto    &statistics = scene_.solver(b).statistics();
        nlohmann::json body;
        body["name"] = scene_.body(b).name();
        body["mesh"] = scene_.body_parameters()[b].mesh.description();
        body["n_cells"] =
          scene_.body(b).triangulation().n_global_active_cells();
        body["n_dofs"]           = scene_.body(b).n_dofs();
        body["stiffness_solver"] = {{"name", scene_.solver(b).name()},
                                    {"setup_time_s", statistics.setup_time},
                                    {"solve_time_s", statistics.solve_time},
                                    {"n_solves", statistics.n_solves},
                                    {"factor_nonzeros",
                                     statistics.factor_nonzeros},
                                    {"factor_flops", statistics.factor_flops},
                                    {"iterations", statistics.iterations}};
        nlohmann::json reactions;
        for (const auto &[id, force] : r.reaction_forces)
          reactions[std::to_string(id)] = to_vector<dim>(force);
        body["results"] = {{"strain_energy", r.strain_energy},
                           {"external_work", r.external_work},
                           {"max_displacement_m", r.max_displacement},
                           {"displacement_l2_norm",
                            scene_.displacements()[b].l2_norm()},
                           {"applied_force", to_vector<dim>(r.applied_force)},
                           {"reaction_force_by_boundary_id", reactions},
                           {"contact_force", to_vector<dim>(r.contact_force)},
                           {"force_imbalance", r.force_imbalance}};

        nlohmann::json tractions = nlohmann::json::array();
        for (const auto &resultant : r.traction_resultants)
          tractions.push_back(
            {{"boundary_id", resultant.boundary_id},
             {"nominal_force", to_vector<dim>(resultant.nominal)},
             {"applied_force", to_vector<dim>(resultant.applied)},
             {"relative_difference", resultant.relative_difference()}});
        body["results"]["traction_resultants"] = tractions;
        bodies.push_back(body);
      }
      json["bodies"] = bodies;

      if (contact_ != nullptr)
      {
        nlohmann::json contact;
        contact["converged"]          = contact_->result().converged;
        contact["reason"]             = contact_->result().reason;
        contact["n_multipliers"]      = contact_->dual().n_multipliers();
        contact["n_rigid_body_modes"] = contact_->dual().n_rigid_body_modes();
        contact["lambda_max_F"]       = contact_->dual().scale();
        contact["n_stiffness_solves"] = contact_->dual().n_stiffness_solves();
        contact["stiffness_setup_time_s"] =
          contact_->dual().stiffness_setup_time();
        contact["stiffness_solve_time_s"] =
          contact_->dual().stiffness_solve_time();
        contact["dual_operator"] = contact_->dual().operator_description();
        contact["dual_operator_assembly_time_s"] =
          contact_->dual().assembly_time();
        contact["qp_wall_time_s"] = contact_->qp_wall_time();
        // the vectors the QPs ran on, and how the multipliers were split
        contact["qp_vectors"] = contact_->result().qp_vectors;
        contact["multipliers_per_process"] =
          contact_->result().multipliers_per_process;
        contact["contact_nodes_per_process"] =
          contact_->dual().contact_nodes_per_process();
        contact["coulomb_changes"] = contact_->result().coulomb_changes;
        // the working set over the normal rows, per QP (WorkingSet)
        nlohmann::json working_sets = nlohmann::json::array();
        for (const auto &w : contact_->result().working_sets)
          working_sets.push_back({{"used", w.used},
                                  {"n_normal_rows", w.n_normal_rows},
                                  {"n_dropped", w.n_dropped},
                                  {"n_separated", w.n_separated},
                                  {"n_added_back", w.n_added},
                                  {"n_dropped_final", w.n_dropped_final},
                                  {"n_rounds", w.n_rounds},
                                  {"reach_m", w.reach},
                                  {"fall_back", w.fall_back}});
        contact["working_sets"] = working_sets;
        if (const auto *tfeti = contact_->tfeti())
        {
          std::vector<unsigned int> per_body;
          for (unsigned int b = 0; b < scene_.elastic_bodies().size(); ++b)
            per_body.push_back(tfeti->n_subdomains_of_body(b));
          contact["decomposition"] = {
            {"method", "tfeti"},
            {"n_subdomains", tfeti->n_subdomains()},
            {"subdomains_per_body", per_body},
            {"n_subdomain_dofs", tfeti->n_primal_dofs()},
            {"subdomains_per_process", tfeti->subdomains_per_process()},
            {"subdomain_dofs_per_process", tfeti->subdomain_dofs_per_process()},
            {"n_contact_multipliers", tfeti->n_contact_multipliers()},
            {"n_gluing_multipliers", tfeti->n_gluing_multipliers()},
            {"n_dirichlet_multipliers", tfeti->n_dirichlet_multipliers()},
            {"coarse_problem_order", tfeti->n_rigid_body_modes()},
            {"coarse_problem_nonzeros", tfeti->coarse_problem().n_nonzeros()},
            {"coarse_factor_nonzeros",
             tfeti->coarse_problem().n_factor_nonzeros()},
            {"coarse_setup_time_s", tfeti->coarse_problem().setup_time()},
            {"decomposition_time_s", tfeti->decomposition_time()},
            {"max_interface_jump_m", tfeti->max_interface_jump()},
            {"relative_interface_jump", tfeti->relative_interface_jump()}};
        }
        else
          contact["decomposition"] = {{"method", "none"}};
        if (!contact_->primal_json().empty())
          contact["primal"] = nlohmann::json::parse(contact_->primal_json());
        nlohmann::json solves = nlohmann::json::array();
        for (const auto &q : contact_->result().qp_statistics)
          solves.push_back(nlohmann::json::parse(q.to_json()));
        contact["qp_solves"]        = solves;
        nlohmann::json pairs        = nlohmann::json::array();
        const auto    &pair_results = contact_->pair_results();
        for (unsigned int p = 0; p < pair_results.size(); ++p)
        {
          const auto &r    = pair_results[p];
          const auto &pair = scene_.pair_parameters()[p].pair;
          pairs.push_back(
            {{"name", pair.name},
             {"slave_body", pair.slave_body + 1},
             {"slave_boundary_id", pair.slave_boundary},
             {"master", scene_.pair_parameters()[p].master_description},
             {"n_nodes", r.n_nodes},
             {"n_separated", r.n_separated},
             {"n_stick", r.n_stick},
             {"n_slip", r.n_slip},
             {"n_contact", r.n_contact},
             {"area", r.area},
             {"min_initial_gap_m", r.min_gap},
             {"max_initial_gap_m", r.max_gap},
             {"normal_force", r.normal_force},
             {"tangential_force", to_vector<dim>(r.tangential_force)},
             {"contact_force", to_vector<dim>(r.contact_force)},
             {"max_pressure_Pa", r.max_pressure},
             {dim == 2 ? "contact_length_m" : "contact_area_m2",
              r.contact_measure}});
        }
        contact["pairs"] = pairs;
        json["contact"]  = contact;
      }
      if (cycles_ != nullptr && !cycles_->empty())
      {
        nlohmann::json cycles = nlohmann::json::array();
        for (const auto &c : *cycles_)
        {
          unsigned int n_dofs = 0;
          for (const auto n : c.n_dofs)
            n_dofs += n;
          nlohmann::json pairs = nlohmann::json::array();
          for (unsigned int p = 0; p < c.pair_nodes.size(); ++p)
            pairs.push_back({{"n_nodes", c.pair_nodes[p]},
                             {"n_in_contact", c.pair_in_contact[p]},
                             {"normal_force", c.pair_normal_force[p]},
                             {"max_pressure_Pa", c.pair_max_pressure[p]}});
          nlohmann::json boxes = nlohmann::json::array();
          for (const auto &[lower, upper] : c.marked_box)
            boxes.push_back(lower[0] > upper[0] ?
                              nlohmann::json() :
                              nlohmann::json{{"lower", to_vector<dim>(lower)},
                                             {"upper", to_vector<dim>(upper)}});
          nlohmann::json zone_boxes = nlohmann::json::array();
          for (const auto &[lower, upper] : c.zone_box)
            zone_boxes.push_back(
              lower[0] > upper[0] ?
                nlohmann::json() :
                nlohmann::json{{"lower", to_vector<dim>(lower)},
                               {"upper", to_vector<dim>(upper)}});
          cycles.push_back({{"cycle", c.cycle},
                            {"marked_cells_box_by_body", boxes},
                            {"n_zone_cells", c.n_zone_cells},
                            {"zone_cells_box_by_body", zone_boxes},
                            {"n_cells_by_body", c.n_cells},
                            {"n_dofs_by_body", c.n_dofs},
                            {"n_dofs", n_dofs},
                            {"n_contact_nodes", c.n_contact_nodes},
                            {"n_in_contact", c.n_in_contact},
                            {"n_marked_cells", c.n_marked_cells},
                            {"qp_iterations", c.qp_iterations},
                            {"qp_hessian_products", c.qp_hessian_products},
                            {"wall_time_s", c.wall_time},
                            {"pairs", pairs}});
        }
        json["refinement"] = {{"cycles", cycles}};
      }
      json["units"] = dim == 2 ? "SI; forces in N/m and energies in J/m "
                                 "(plane strain, per metre of thickness)" :
                                 "SI; forces in N, energies in J";
      return json.dump(2) + "\n";
    }


    template <int dim>
    void
    ResultsReport<dim>::write_output(
      io::OutputFolder                            &folder,
      const bool                                   write_vtu,
      const std::string                           &suffix,
      const double                                 time,
      std::vector<std::pair<double, std::string>> *series) const
    {
      const unsigned int n_ranks =
        dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
      const unsigned int rank =
        dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
      const typename ContactStage<dim>::Surfaces              no_surfaces;
      const std::vector<typename ContactStage<dim>::Surfaces> no_iterates;
      const auto                                             &surfaces =
        contact_ != nullptr ? contact_->surfaces() : no_surfaces;
      const auto &iterates =
        contact_ != nullptr ? contact_->coulomb_iterates() : no_iterates;

      // A contact surface: one file; under MPI one piece per process (the
      // slave faces of the cells it owns: on a distributed mesh no process
      // has them all) and STEM.pvtu as the record of the pieces.  Returns
      // the file to list.
      const std::vector<io::ContactSurfaceMesh<dim>> no_meshes;
      const auto                                    &meshes =
        contact_ != nullptr ? contact_->surface_meshes() : no_meshes;
      const auto write_surface =
        [&](const std::string                                      &stem,
            const unsigned int                                      p,
            const typename ContactStage<dim>::Surfaces::value_type &surface)
      {
        if (n_ranks == 1)
        {
          folder.write(stem + ".vtu",
                       [&](std::ostream &out) {
                         io::write_contact_surface<dim>(out,
                                                        meshes[p],
                                                        surface);
                       });
          return stem + ".vtu";
        }
        folder.write(
          stem + "_rank_" + std::to_string(rank) + ".vtu",
          [&](std::ostream &out)
          { io::write_contact_surface<dim>(out, meshes[p], surface, rank); });
        std::vector<std::string> pieces;
        for (unsigned int r = 0; r < n_ranks; ++r)
          pieces.push_back(stem + "_rank_" + std::to_string(r) + ".vtu");
        if (rank == 0)
        {
          folder.write(stem + ".pvtu",
                       [&](std::ostream &out)
                       { io::write_contact_surface_record(out, pieces); });
          for (unsigned int r = 1; r < n_ranks; ++r)
            folder.list_file_of_other_process(pieces[r]);
        }
        return stem + ".pvtu";
      };
      std::vector<std::string> contact_files;
      for (unsigned int p = 0; p < surfaces.size(); ++p)
        contact_files.push_back(write_surface(
          "contact_" + std::to_string(p + 1) + suffix, p, surfaces[p]));
      // Coulomb iterates, likewise
      if (!iterates.empty())
      {
        std::vector<std::pair<double, std::string>> series;
        for (unsigned int k = 0; k < iterates.size(); ++k)
          for (unsigned int p = 0; p < iterates[k].size(); ++p)
            series.emplace_back(
              k + 1,
              write_surface("contact_" + std::to_string(p + 1) + suffix +
                              "_iterate_" + std::to_string(k + 1),
                            p,
                            iterates[k][p]));
        if (rank == 0)
          folder.write("coulomb_iterates" + suffix + ".pvd",
                       [&](std::ostream &out) { io::write_pvd(out, series); });
      }
      if (write_vtu)
        io::write_solution<dim>(folder,
                                scene_.elastic_bodies(),
                                scene_.displacements(),
                                contact_files,
                                suffix,
                                time,
                                series);
    }


    template <int dim>
    void
    ResultsReport<dim>::write_fclib_problem(io::OutputFolder  &folder,
                                            const std::string &form) const
    {
      Assert(contact_ != nullptr, dealii::ExcInternalError());
      try
      {
        const auto                                &result = contact_->result();
        std::vector<const fem::ElasticBody<dim> *> bodies;
        for (const auto &body : scene_.elastic_bodies())
          bodies.push_back(body.get());
        const auto *dual =
          dynamic_cast<const contact::DualProblem<dim> *>(&contact_->dual());
        AssertThrow(dual != nullptr,
                    dealii::ExcMessage(
                      "The FCLIB export needs the undecomposed dual "
                      "(`set Method = none' in `subsection Decomposition')."));
        // the solution only if there is one
        fclib::write_scene_problem<dim>(folder,
                                        fclib::export_form_names.value(form),
                                        bodies,
                                        contact_->discretization(),
                                        *dual,
                                        result.converged ?
                                          result.lambda :
                                          dealii::Vector<double>(),
                                        parameter_file_);
      }
      catch (const dealii::ExceptionBase &e)
      {
        AssertThrow(false,
                    dealii::ExcMessage(
                      fclib::exception_message(e) + " " +
                      io::parameter_location("Output", "FCLIB problem")));
      }
    }


    template <int dim>
    void
    ResultsReport<dim>::write_records(io::OutputFolder               &folder,
                                      const dealii::ParameterHandler &prm,
                                      const dealii::TimerOutput &timer) const
    {
      folder.write("results.txt",
                   [this](std::ostream &out) { out << results_text(); });
      folder.write("statistics.json",
                   [&](std::ostream &out) { out << statistics_json(timer); });
      folder.write("used_parameters.prm",
                   [&](std::ostream &out)
                   {
                     out << "# Parameters used by dualcontact "
                         << DUALCONTACT_VERSION << " for " << parameter_file_
                         << "\n";
                     prm.print_parameters(
                       out,
                       dealii::ParameterHandler::ShortPRM |
                         dealii::ParameterHandler::KeepDeclarationOrder);
                   });
    }


    template class ResultsReport<2>;
    template class ResultsReport<3>;
  } // namespace driver
} // namespace dualcontact
