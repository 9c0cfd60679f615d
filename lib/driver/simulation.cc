#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <driver/simulation.h>
#include <io/contact_surface_writer.h>
#include <io/file_locator.h>
#include <io/parameter_file.h>
#include <io/solution_writer.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
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
      write_vtu_              = prm.get_bool("Write VTU");
      write_coulomb_iterates_ = prm.get_bool("Write Coulomb iterates");
      status_tolerance_       = prm.get_double("Contact status tolerance");
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

      const unsigned int n_obstacles = prm.get_integer("Number of obstacles");
      obstacle_parameters_.resize(n_obstacles);
      for (unsigned int n = 0; n < n_obstacles; ++n)
      {
        const std::string name = "Obstacle " + std::to_string(n + 1);
        prm.enter_subsection(name);
        obstacle_parameters_[n].parse_parameters(prm, name);
        prm.leave_subsection();
      }
      const unsigned int n_pairs = prm.get_integer("Number of contact pairs");
      pair_parameters_.resize(n_pairs);
      for (unsigned int n = 0; n < n_pairs; ++n)
      {
        const std::string name = "Contact pair " + std::to_string(n + 1);
        prm.enter_subsection(name);
        pair_parameters_[n].parse_parameters(prm,
                                             name,
                                             n_bodies,
                                             obstacle_parameters_);
        prm.leave_subsection();
      }
      qp_parameters_.parse_parameters(prm);
      smalse_parameters_.parse_parameters(prm);
      coulomb_parameters_.parse_parameters(prm);
      dual_parameters_.parse_parameters(prm);

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
    bool
    Simulation<dim>::run()
    {
      const bool has_contact = !pair_parameters_.empty();
      console_ << "Scene: " << dim << "D" << (dim == 2 ? " (plane strain)" : "")
               << ", " << body_parameters_.size() << " bod"
               << (body_parameters_.size() == 1 ? "y" : "ies") << ", FE_Q("
               << fe_degree_ << "), stiffness solver "
               << solvers_.front()->name();
      if (has_contact)
        console_ << ", " << pair_parameters_.size() << " contact pair"
                 << (pair_parameters_.size() == 1 ? "" : "s") << ", QP solver "
                 << qp_parameters_.solver;
      console_ << std::endl;

      run_phase("Mesh", [this]() { create_meshes(); });
      run_phase("Setup", [this]() { setup(); });
      run_phase("Assembly", [this]() { assemble(); });
      if (has_contact)
      {
        run_phase("Contact search", [this]() { discretize_contact(); });
        run_phase("Factorization", [this]() { setup_dual_problem(); });
        run_phase("QP", [this]() { solve_contact(); });
        run_phase("Recovery", [this]() { recover(); });
      }
      else
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
      for (unsigned int p = 0; p < pair_results_.size(); ++p)
      {
        const PairResults &r = pair_results_[p];
        std::ostringstream line;
        line << std::setprecision(6) << "  " << pair_parameters_[p].pair.name
             << ": normal force " << r.normal_force
             << (dim == 2 ? " N/m" : " N") << ", max pressure "
             << r.max_pressure << " Pa, " << r.n_nodes
             << " nodes: " << r.n_separated << " separated, " << r.n_stick
             << " stick, " << r.n_slip << " slip";
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

      if (has_contact && !contact_result_.converged)
      {
        std::ostringstream message;
        message << "The contact solver did NOT converge: "
                << contact_result_.reason << ".";
        if (!contact_result_.qp_statistics.empty())
        {
          const auto &last = contact_result_.qp_statistics.back();
          message << std::setprecision(3) << " Last QP: " << last.solver << ", "
                  << qp::to_string(last.reason) << " after " << last.iterations
                  << " iterations, criterion " << last.final_criterion
                  << " (tolerance " << last.tolerance
                  << "), KKT residuals: stationarity " << last.kkt.stationarity
                  << ", feasibility " << last.kkt.feasibility
                  << ", complementarity " << last.kkt.complementarity
                  << " (||b|| " << last.norm_b << ")";
          if (!last.message.empty())
            message << "; " << last.message;
          message << ".";
        }
        if (!contact_result_.coulomb_changes.empty())
          message << std::setprecision(3) << " Last Coulomb change of psi: "
                  << contact_result_.coulomb_changes.back() << ".";
        message << " The output was written all the same, flagged as not "
                   "converged.";
        std::cerr << "\nError: " << message.str() << std::endl;
        return false;
      }
      return true;
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
        const unsigned int b          = triangulations_.size();
        bool               in_contact = false;
        for (const auto &pair : pair_parameters_)
          in_contact = in_contact || pair.involves_body(b);
        parameters.check_mesh(*triangulation, in_contact);
        details_.push_back(
          parameters.name + ": " + parameters.mesh.description() + ", " +
          std::to_string(triangulation->n_active_cells()) + " cells");
        triangulations_.push_back(triangulation);
      }
      for (const auto &pair : pair_parameters_)
        pair.check_mesh(triangulations_);
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
    Simulation<dim>::discretize_contact()
    {
      std::vector<const fem::ElasticBody<dim> *> bodies;
      for (const auto &body : bodies_)
        bodies.push_back(body.get());
      std::vector<contact::ContactPair<dim>> pairs;
      for (const auto &parameters : pair_parameters_)
        pairs.push_back(parameters.pair);
      contact_ =
        std::make_unique<contact::ContactDiscretization<dim>>(bodies, pairs);
      for (unsigned int p = 0; p < pair_parameters_.size(); ++p)
      {
        const auto        &summary = contact_->pair_summaries()[p];
        const auto        &pair    = pair_parameters_[p].pair;
        std::ostringstream line;
        line << std::setprecision(4) << summary.name << " (Body "
             << pair.slave_body + 1 << " boundary " << pair.slave_boundary
             << " on " << pair_parameters_[p].master_description;
        if (pair.obstacle)
          line << ": " << pair.obstacle->description();
        else
          line << " boundary " << pair.master_boundary;
        line << "): " << summary.n_nodes << " contact nodes, gap "
             << summary.min_gap << " .. " << summary.max_gap << " m, area "
             << summary.area << (dim == 2 ? " m" : " m^2");
        details_.push_back(line.str());
      }
    }


    template <int dim>
    void
    Simulation<dim>::setup_dual_problem()
    {
      std::vector<const fem::ElasticBody<dim> *> bodies;
      for (const auto &body : bodies_)
        bodies.push_back(body.get());
      dealii::ParameterHandler &prm = prm_;
      dual_ = std::make_unique<contact::DualProblem<dim>>(
        bodies,
        *contact_,
        [&prm]() { return fem::StiffnessSolver::create(prm); },
        dual_parameters_);
      std::ostringstream line;
      line << std::setprecision(4) << dual_->n_multipliers() << " multipliers ("
           << dual_->n_contact_nodes() << " normal, "
           << dual_->n_multipliers() - dual_->n_contact_nodes()
           << " tangential), " << dual_->n_rigid_body_modes()
           << " rigid-body modes, lambda_max(F) " << dual_->scale() << " m/N";
      details_.push_back(line.str());
      details_.push_back("Dual operator: " + dual_->operator_description());
    }


    template <int dim>
    void
    Simulation<dim>::solve_contact()
    {
      contact::ContactSolver<dim> solver(*dual_,
                                         qp_parameters_,
                                         smalse_parameters_,
                                         coulomb_parameters_);
      std::function<void(const typename contact::ContactSolver<dim>::Result &)>
        on_iterate;
      if (write_coulomb_iterates_ && dual_->has_coulomb_friction())
        on_iterate = [this](const auto &iterate)
        {
          coulomb_iterates_.push_back(
            contact_surfaces(iterate.lambda, iterate.displacements));
        };
      contact_result_ = solver.solve(on_iterate);

      qp_wall_time_ = 0;
      for (unsigned int k = 0; k < contact_result_.qp_statistics.size(); ++k)
      {
        const auto        &q = contact_result_.qp_statistics[k];
        std::ostringstream line;
        line << std::setprecision(3) << "QP " << k + 1 << ": " << q.solver
             << ", " << qp::to_string(q.reason) << ", " << q.iterations
             << " iterations";
        if (q.n_outer > 0)
          line << " (" << q.n_outer << " SMALSE-M outer)";
        line << ", " << q.n_hessian_products << " Hessian products, "
             << q.wall_time << " s, criterion " << q.final_criterion;
        if (k < contact_result_.coulomb_changes.size())
          line << ", Coulomb change of psi "
               << contact_result_.coulomb_changes[k];
        details_.push_back(line.str());
        qp_wall_time_ += q.wall_time;
      }
      details_.push_back((contact_result_.converged ? "" : "NOT CONVERGED: ") +
                         contact_result_.reason + ", " +
                         std::to_string(dual_->n_stiffness_solves()) +
                         " stiffness solves");
    }


    template <int dim>
    void
    Simulation<dim>::recover()
    {
      // the contact solver recovered the displacements already; recovering
      // here again (one K^# per body) keeps the phases' timings apart
      dual_->recover(contact_result_.lambda, displacements_);
      surfaces_ = contact_surfaces(contact_result_.lambda, displacements_);

      pair_results_.assign(pair_parameters_.size(), PairResults());
      for (unsigned int p = 0; p < pair_parameters_.size(); ++p)
      {
        PairResults &r       = pair_results_[p];
        const auto  &summary = contact_->pair_summaries()[p];
        r.min_gap            = summary.min_gap;
        r.max_gap            = summary.max_gap;
        r.area               = summary.area;
      }
      const unsigned int n = contact_->n_nodes();
      for (unsigned int i = 0; i < n; ++i)
      {
        const auto  &node = contact_->nodes()[i];
        PairResults &r    = pair_results_[node.pair];
        r.normal_force += contact_result_.lambda(i);
        const int j = dual_->frictional_index(i);
        if (j >= 0)
          for (unsigned int k = 0; k + 1 < dim; ++k)
            r.tangential_force +=
              contact_result_.lambda(n + (dim - 1) * j + k) * node.tangents[k];
      }
      for (unsigned int p = 0; p < surfaces_.size(); ++p)
      {
        PairResults &r = pair_results_[p];
        for (const auto &node : surfaces_[p])
        {
          ++r.n_nodes;
          r.max_pressure = std::max(r.max_pressure, node.pressure);
          if (node.status == io::contact_status::separated)
            ++r.n_separated;
          else if (node.status == io::contact_status::stick)
            ++r.n_stick;
          else if (node.status == io::contact_status::slip)
            ++r.n_slip;
          else
            ++r.n_contact;
        }
      }
    }


    template <int dim>
    std::vector<std::vector<io::ContactSurfaceNode<dim>>>
    Simulation<dim>::contact_surfaces(
      const dealii::Vector<double>              &lambda,
      const std::vector<dealii::Vector<double>> &displacements) const
    {
      const unsigned int     n = contact_->n_nodes();
      dealii::Vector<double> u(contact_->n_dofs());
      for (unsigned int b = 0; b < displacements.size(); ++b)
        for (unsigned int k = 0; k < displacements[b].size(); ++k)
          u(contact_->body_offset(b) + k) = displacements[b](k);
      dealii::Vector<double> bn(n), bt((dim - 1) * n);
      contact_->normal_matrix().vmult(bn, u);
      contact_->tangential_matrix().vmult(bt, u);
      bt += contact_->tangential_offset();
      const dealii::Vector<double> c = contact_->normal_bound();

      std::vector<double> max_lambda(pair_parameters_.size(), 0.);
      for (unsigned int i = 0; i < n; ++i)
        max_lambda[contact_->nodes()[i].pair] =
          std::max(max_lambda[contact_->nodes()[i].pair], lambda(i));

      const auto &psi_first  = dual_->slip_bounds_first();
      const auto &psi_second = dual_->slip_bounds_second();
      std::vector<std::vector<io::ContactSurfaceNode<dim>>> surfaces(
        pair_parameters_.size());
      for (unsigned int i = 0; i < n; ++i)
      {
        const auto                 &node = contact_->nodes()[i];
        const contact::FrictionLaw &law =
          pair_parameters_[node.pair].pair.friction;
        io::ContactSurfaceNode<dim> out;
        out.position = node.position;
        out.normal   = node.normal;
        out.pressure = lambda(i) / node.weight;
        out.weight   = node.weight;
        out.gap      = c(i) - bn(i);
        for (unsigned int k = 0; k + 1 < dim; ++k)
          out.slip += bt((dim - 1) * i + k) * node.tangents[k];

        const bool separated =
          !(lambda(i) > status_tolerance_ * max_lambda[node.pair]);
        const int j           = dual_->frictional_index(i);
        double    utilization = 1; // |lambda_T| / bound, 1 = on the boundary
        if (j >= 0)
        {
          std::array<double, dim - 1> lt;
          for (unsigned int k = 0; k + 1 < dim; ++k)
          {
            lt[k] = lambda(n + (dim - 1) * j + k);
            out.tangential_traction += lt[k] / node.weight * node.tangents[k];
          }
          if (dim == 3 && law.is_orthotropic())
          {
            double sum = 0;
            for (unsigned int k = 0; k + 1 < dim; ++k)
            {
              const double bound = k == 0 ? psi_first[j] : psi_second[j];
              sum += bound > 0 ? std::pow(lt[k] / bound, 2) :
                                 (lt[k] != 0 ? 1e300 : 1);
            }
            utilization = std::sqrt(sum);
          }
          else
          {
            double norm = 0;
            for (unsigned int k = 0; k + 1 < dim; ++k)
              norm += lt[k] * lt[k];
            norm        = std::sqrt(norm);
            utilization = psi_first[j] > 0 ? norm / psi_first[j] : 1;
          }
        }
        out.status = separated ? io::contact_status::separated :
                     j < 0     ? io::contact_status::frictionless_contact :
                     utilization >= 1 - status_tolerance_ ?
                             io::contact_status::slip :
                             io::contact_status::stick;
        surfaces[node.pair].push_back(out);
      }
      return surfaces;
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
      if (!pair_parameters_.empty())
      {
        out << "contact.converged = " << (contact_result_.converged ? 1 : 0)
            << "\n";
        out << "contact.n_qp_solves = " << contact_result_.qp_statistics.size()
            << "\n";
        out << "contact.n_multipliers = " << dual_->n_multipliers() << "\n";
      }
      for (unsigned int p = 0; p < pair_results_.size(); ++p)
      {
        const PairResults &r      = pair_results_[p];
        const std::string  prefix = "pair_" + std::to_string(p + 1) + ".";
        const double       scale =
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
        out << prefix << "max_pressure = " << format_number(r.max_pressure)
            << "\n";
      }
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

      if (!pair_parameters_.empty())
      {
        nlohmann::json contact;
        contact["converged"]          = contact_result_.converged;
        contact["reason"]             = contact_result_.reason;
        contact["n_multipliers"]      = dual_->n_multipliers();
        contact["n_rigid_body_modes"] = dual_->n_rigid_body_modes();
        contact["lambda_max_F"]       = dual_->scale();
        contact["n_stiffness_solves"] = dual_->n_stiffness_solves();
        contact["stiffness_setup_time_s"] = dual_->stiffness_setup_time();
        contact["stiffness_solve_time_s"] = dual_->stiffness_solve_time();
        contact["dual_operator"]          = dual_->operator_description();
        contact["dual_operator_assembly_time_s"] = dual_->assembly_time();
        contact["qp_wall_time_s"]     = qp_wall_time_;
        contact["coulomb_changes"]    = contact_result_.coulomb_changes;
        nlohmann::json solves         = nlohmann::json::array();
        for (const auto &q : contact_result_.qp_statistics)
          solves.push_back(nlohmann::json::parse(q.to_json()));
        contact["qp_solves"] = solves;
        nlohmann::json pairs = nlohmann::json::array();
        for (unsigned int p = 0; p < pair_results_.size(); ++p)
        {
          const PairResults &r    = pair_results_[p];
          const auto        &pair = pair_parameters_[p].pair;
          pairs.push_back(
            {{"name", pair.name},
             {"slave_body", pair.slave_body + 1},
             {"slave_boundary_id", pair.slave_boundary},
             {"master", pair_parameters_[p].master_description},
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
             {"max_pressure_Pa", r.max_pressure}});
        }
        contact["pairs"] = pairs;
        json["contact"]  = contact;
      }
      json["units"] = dim == 2 ? "SI; forces in N/m and energies in J/m "
                                 "(plane strain, per metre of thickness)" :
                                 "SI; forces in N, energies in J";
      return json.dump(2) + "\n";
    }


    template <int dim>
    void
    Simulation<dim>::write_output()
    {
      io::OutputFolder        &folder = *output_folder_;
      std::vector<std::string> contact_files;
      for (unsigned int p = 0; p < surfaces_.size(); ++p)
      {
        const std::string name = "contact_" + std::to_string(p + 1) + ".vtu";
        folder.write(name,
                     [&](std::ostream &out)
                     { io::write_contact_surface<dim>(out, surfaces_[p]); });
        contact_files.push_back(name);
      }
      if (!coulomb_iterates_.empty())
      {
        std::vector<std::pair<double, std::string>> series;
        for (unsigned int k = 0; k < coulomb_iterates_.size(); ++k)
          for (unsigned int p = 0; p < coulomb_iterates_[k].size(); ++p)
          {
            const std::string name = "contact_" + std::to_string(p + 1) +
                                     "_iterate_" + std::to_string(k + 1) +
                                     ".vtu";
            folder.write(name,
                         [&](std::ostream &out) {
                           io::write_contact_surface<dim>(
                             out, coulomb_iterates_[k][p]);
                         });
            series.emplace_back(k + 1, name);
          }
        folder.write("coulomb_iterates.pvd",
                     [&](std::ostream &out) { io::write_pvd(out, series); });
      }
      if (write_vtu_)
        io::write_solution<dim>(folder, bodies_, displacements_, contact_files);
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
