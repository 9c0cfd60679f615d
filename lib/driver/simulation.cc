#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <driver/simulation.h>
#include <io/file_locator.h>
#include <io/parameter_file.h>
#include <io/solution_writer.h>

#include <nlohmann/json.hpp>

#include <algorithm>
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
    Simulation<dim>::Simulation(dealii::ParameterHandler   &prm,
                                const std::string          &parameter_file,
                                dealii::ConditionalOStream &console)
        : prm_(prm)
        , parameter_file_(parameter_file)
        , console_(console)
        , is_output_rank_(
            dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        , timer_(console,
                 dealii::TimerOutput::never,
                 dealii::TimerOutput::wall_times)
    {
      prm.enter_subsection("Discretization");
      fe_degree_ = prm.get_integer("Finite element degree");
      prm.leave_subsection();

      prm.enter_subsection("Output");
      output_folder_ = std::make_unique<io::OutputFolder>(
        prm.get("Output folder"),
        io::parameter_location("Output", "Output folder"));
      write_vtu_ = prm.get_bool("Write VTU");
      prm.leave_subsection();

      const std::string  folder   = io::folder_of(parameter_file);
      const unsigned int n_bodies = prm.get_integer("Number of bodies");
      body_parameters_.resize(n_bodies);
      for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const std::string name = "Body " + std::to_string(b + 1);
        prm.enter_subsection(name);
        body_parameters_[b].parse_parameters(prm, name, folder);
        prm.leave_subsection();
      }

      for (unsigned int b = 0; b < n_bodies; ++b)
        solvers_.push_back(fem::StiffnessSolver::create(prm));
    }


    template <int dim>
    Simulation<dim>::~Simulation() = default;


    template <int dim>
    template <typename Phase>
    void
    Simulation<dim>::run_phase(const std::string &name, const Phase &phase)
    {
      details_.clear();
      dealii::Timer timer;
      {
        dealii::TimerOutput::Scope scope(timer_, name);
        phase();
      }
      timer.stop();
      std::ostringstream line;
      line << "  " << std::left << std::setw(16) << name << std::right
           << std::fixed << std::setprecision(3) << std::setw(9)
           << timer.wall_time() << " s";
      console_ << line.str() << std::endl;
      for (const auto &detail : details_)
        console_ << "      " << detail << std::endl;
    }


    template <int dim>
    void
    Simulation<dim>::run()
    {
      console_ << "Scene: " << dim << "D" << (dim == 2 ? " (plane strain)" : "")
               << ", " << body_parameters_.size() << " bod"
               << (body_parameters_.size() == 1 ? "y" : "ies") << ", FE_Q("
               << fe_degree_ << "), stiffness solver "
               << solvers_.front()->name() << std::endl;

      run_phase("Mesh", [this]() { create_meshes(); });
      run_phase("Setup", [this]() { setup(); });
      run_phase("Assembly", [this]() { assemble(); });
      run_phase("Solve", [this]() { solve(); });
      run_phase("Postprocessing", [this]() { postprocess(); });

      console_ << "Results:" << std::endl;
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        std::ostringstream line;
        line << std::setprecision(6) << "  " << bodies_[b]->name()
             << ": strain energy " << results_[b].strain_energy
             << (dim == 2 ? " J/m" : " J") << ", max displacement "
             << results_[b].max_displacement << " m";
        console_ << line.str() << std::endl;
      }

      if (is_output_rank_)
      {
        run_phase("Output", [this]() { write_output(); });
        write_records();
      }

      std::string files;
      for (const auto &name : output_folder_->file_names())
        files += (files.empty() ? "" : ", ") + name;
      console_ << "Output written to `" << output_folder_->path()
               << "/': " << files << std::endl;
      if (write_vtu_)
        console_ << "Open `" << output_folder_->path()
                 << "/solution.pvd' in ParaView." << std::endl;
    }


    template <int dim>
    void
    Simulation<dim>::create_meshes()
    {
      for (auto &parameters : body_parameters_)
      {
        auto triangulation = std::make_shared<dealii::Triangulation<dim>>();
        parameters.mesh.create(*triangulation,
                               parameters.placement,
                               parameters.name);
        parameters.check_mesh(*triangulation);
        details_.push_back(
          parameters.name + ": " + parameters.mesh.description() + ", " +
          std::to_string(triangulation->n_active_cells()) + " cells");
        triangulations_.push_back(triangulation);
      }
    }


    template <int dim>
    void
    Simulation<dim>::setup()
    {
      for (unsigned int b = 0; b < body_parameters_.size(); ++b)
      {
        const BodyParameters<dim> &parameters = body_parameters_[b];
        auto                       body =
          std::make_unique<fem::ElasticBody<dim>>(parameters.name,
                                                  triangulations_[b],
                                                  fe_degree_,
                                                  parameters.materials);
        body->set_dirichlet_conditions(parameters.dirichlet);
        body->set_traction_conditions(parameters.tractions);
        if (parameters.has_body_force)
          body->set_body_force(parameters.body_force);
        body->setup();
        details_.push_back(parameters.name + ": " +
                           std::to_string(body->n_dofs()) + " dofs");
        bodies_.push_back(std::move(body));
      }
    }


    template <int dim>
    void
    Simulation<dim>::assemble()
    {
      for (auto &body : bodies_)
        body->assemble();
    }


    template <int dim>
    void
    Simulation<dim>::solve()
    {
      displacements_.resize(bodies_.size());
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        bodies_[b]->solve(*solvers_[b], displacements_[b]);
        const auto        &statistics = solvers_[b]->statistics();
        std::ostringstream line;
        line << std::setprecision(3) << bodies_[b]->name() << ": "
             << solvers_[b]->name() << ", setup " << statistics.setup_time
             << " s, solve " << statistics.solve_time << " s";
        if (statistics.factor_nonzeros > 0)
          line << ", factor nonzeros " << statistics.factor_nonzeros;
        if (statistics.iterations > 0)
          line << ", " << statistics.iterations << " iterations";
        details_.push_back(line.str());
      }
    }


    template <int dim>
    void
    Simulation<dim>::postprocess()
    {
      results_.resize(bodies_.size());
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        const fem::ElasticBody<dim>  &body = *bodies_[b];
        const dealii::Vector<double> &u    = displacements_[b];
        BodyResults                  &r    = results_[b];
        r.strain_energy                    = body.strain_energy(u);
        r.external_work                    = body.external_work(u);
        r.max_displacement                 = body.max_displacement(u);
        r.applied_force                    = body.applied_force();
        r.reaction_forces                  = body.reaction_forces(u);
      }
    }


    template <int dim>
    std::string
    Simulation<dim>::results_text() const
    {
      std::ostringstream out;
      out << "# dualcontact results, SI units"
          << (dim == 2 ? " (2D plane strain: per metre of thickness)" : "")
          << "\n";
      out << "dimension = " << dim << "\n";
      out << "n_bodies = " << bodies_.size() << "\n";
      double total_energy = 0, total_work = 0;
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        const BodyResults &r      = results_[b];
        const std::string  prefix = "body_" + std::to_string(b + 1) + ".";
        // the size of the forces in this body, to recognize round-off
        // zeros: the largest resultant, or energy / displacement when
        // nothing is loaded (prescribed displacements only)
        double force_scale = r.applied_force.norm();
        for (const auto &[id, force] : r.reaction_forces)
          force_scale = std::max(force_scale, force.norm());
        if (r.max_displacement > 0)
          force_scale =
            std::max(force_scale, r.strain_energy / r.max_displacement);
        out << prefix
            << "n_cells = " << bodies_[b]->triangulation().n_active_cells()
            << "\n";
        out << prefix << "n_dofs = " << bodies_[b]->n_dofs() << "\n";
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
        total_energy += r.strain_energy;
        total_work += r.external_work;
      }
      out << "total.strain_energy = " << format_number(total_energy) << "\n";
      out << "total.external_work = " << format_number(total_work) << "\n";
      return out.str();
    }


    template <int dim>
    std::string
    Simulation<dim>::statistics_json() const
    {
      nlohmann::json json;
      json["program"]        = "dualcontact";
      json["version"]        = DUALCONTACT_VERSION;
      json["parameter_file"] = parameter_file_;
      json["dimension"]      = dim;
      json["fe_degree"]      = fe_degree_;
      json["mpi_processes"] =
        dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);

      nlohmann::json timing;
      for (const auto &[section, seconds] :
           timer_.get_summary_data(dealii::TimerOutput::total_wall_time))
        timing[section] = seconds;
      json["wall_time_s"] = timing;

      nlohmann::json bodies = nlohmann::json::array();
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        const BodyResults &r          = results_[b];
        const auto        &statistics = solvers_[b]->statistics();
        nlohmann::json     body;
        body["name"]             = bodies_[b]->name();
        body["mesh"]             = body_parameters_[b].mesh.description();
        body["n_cells"]          = bodies_[b]->triangulation().n_active_cells();
        body["n_dofs"]           = bodies_[b]->n_dofs();
        body["stiffness_solver"] = {{"name", solvers_[b]->name()},
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
                           {"applied_force", to_vector<dim>(r.applied_force)},
                           {"reaction_force_by_boundary_id", reactions}};
        bodies.push_back(body);
      }
      json["bodies"] = bodies;
      json["units"]  = dim == 2 ? "SI; forces in N/m and energies in J/m "
                                  "(plane strain, per metre of thickness)" :
                                  "SI; forces in N, energies in J";
      return json.dump(2) + "\n";
    }


    template <int dim>
    void
    Simulation<dim>::write_output()
    {
      io::OutputFolder &folder = *output_folder_;
      if (write_vtu_)
        io::write_solution<dim>(folder, bodies_, displacements_);
    }


    template <int dim>
    void
    Simulation<dim>::write_records()
    {
      io::OutputFolder &folder = *output_folder_;
      folder.write("results.txt",
                   [this](std::ostream &out) { out << results_text(); });
      folder.write("statistics.json",
                   [this](std::ostream &out) { out << statistics_json(); });
      folder.write("used_parameters.prm",
                   [this](std::ostream &out)
                   {
                     out << "# Parameters used by dualcontact "
                         << DUALCONTACT_VERSION << " for " << parameter_file_
                         << "\n";
                     prm_.print_parameters(
                       out,
                       dealii::ParameterHandler::ShortPRM |
                         dealii::ParameterHandler::KeepDeclarationOrder);
                   });
      folder.commit();
    }


    template class Simulation<2>;
    template class Simulation<3>;
  } // namespace driver
} // namespace dualcontact
