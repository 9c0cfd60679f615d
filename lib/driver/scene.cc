#include <deal.II/base/mpi.h>
#include <deal.II/distributed/shared_tria.h>

#include <decomposition/decomposition_parameters.h>
#include <driver/scene.h>
#include <fem/trilinos_solver.h>
#include <io/file_locator.h>
#include <util/machine.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace dualcontact
{
  namespace driver
  {
    template <int dim>
    void
    configure_solver(fem::StiffnessSolver        &solver,
                     const fem::ElasticBody<dim> &body)
    {
      if (auto *trilinos = dynamic_cast<fem::TrilinosSolver *>(&solver))
      {
        trilinos->set_block_size(dim);
        trilinos->set_locally_owned_rows(
          body.dof_handler().locally_owned_dofs());
      }
    }


    template <int dim>
    Scene<dim>::Scene(dealii::ParameterHandler &prm,
                      const std::string        &parameter_file)
    {
      prm.enter_subsection("Discretization");
      fe_degree_ = prm.get_integer("Finite element degree");
      curved_load_mapping_degree_ =
        prm.get_integer("Curved load mapping degree");
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

      for (unsigned int b = 0; b < n_bodies; ++b)
        solvers_.push_back(fem::StiffnessSolver::create(prm));
      // `Solver = automatic' under MPI: cholmod, a whole factor on every
      // process, while those copies fit `Decomposition/Memory limit' on
      // this machine; mumps, spread over the processes, beyond (setup())
      prm.enter_subsection("Stiffness solver");
      const bool automatic = prm.get("Solver") == "automatic";
      prm.leave_subsection();
      decomposition_.parse_parameters(prm);
      factor_limit_ = decomposition_.memory_limit;
      if (automatic && dealii::Utilities::MPI::job_supports_mpi() &&
          dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
        for (unsigned int b = 0; b < n_bodies; ++b)
          spread_solvers_.push_back(fem::StiffnessSolver::create(prm, "mumps"));

      prm.enter_subsection("Dual problem");
      const double memory_limit = prm.get_double("Memory limit");
      prm.leave_subsection();
      check_size_estimate(memory_limit);
    }


    template <int dim>
    void
    Scene<dim>::check_size_estimate(const double memory_limit) const
    {
      // A lower bound of the memory per cell: the triangulation and DoF
      // handler (about 0.5 kB per cell in 2D, 1 kB in 3D) and one row of the
      // stiffness matrix per dof (dim p^dim dofs per cell, dim (2p+1)^dim
      // entries of 12 bytes per row); factors and solver vectors come on
      // top.  What exceeds the limit even so cannot fit.
      const double p              = fe_degree_;
      const double mesh_bytes     = dim == 2 ? 500. : 1000.;
      const double dofs_per_cell  = dim * std::pow(p, dim);
      const double entries_in_row = dim * std::pow(2 * p + 1, dim);
      const double bytes_per_cell =
        mesh_bytes + dofs_per_cell * entries_in_row * 12.;

      double       total_mb      = 0;
      unsigned int largest       = 0;
      double       largest_cells = 0;
      for (unsigned int b = 0; b < body_parameters_.size(); ++b)
      {
        const double cells =
          body_parameters_[b].mesh.estimated_cells(body_parameters_[b].name);
        total_mb += cells * bytes_per_cell / 1048576.;
        if (cells > largest_cells)
        {
          largest_cells = cells;
          largest       = b;
        }
      }
      if (total_mb <= memory_limit)
        return;
      std::ostringstream message;
      message << std::setprecision(3) << "The scene's meshes would not fit "
              << "the memory limit: " << body_parameters_[largest].name
              << " alone would have about " << largest_cells << " cells "
              << body_parameters_[largest].mesh.size_parameters()
              << ", and the meshes and stiffness matrices of all bodies "
                 "would take at least "
              << std::llround(std::min(total_mb, 1e18))
              << " MB (before any factorization), above the `set Memory "
                 "limit' of "
              << std::llround(memory_limit)
              << " MB in `subsection Dual problem'. Lower the refinements or "
                 "subdivisions, or raise the limit if the machine has the "
                 "memory.";
      AssertThrow(false, dealii::ExcMessage(message.str()));
    }


    template <int dim>
    std::vector<const fem::ElasticBody<dim> *>
    Scene<dim>::bodies() const
    {
      std::vector<const fem::ElasticBody<dim> *> bodies;
      for (const auto &body : bodies_)
        bodies.push_back(body.get());
      return bodies;
    }


    template <int dim>
    void
    Scene<dim>::create_meshes(std::vector<std::string> &details)
    {
      const unsigned int n_ranks =
        dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
      for (auto &parameters : body_parameters_)
      {
        // under MPI every process holds the whole mesh, partitioned by METIS
        // into one subdomain per process (the dofs of each subdomain are
        // numbered contiguously: the rows the process owns)
        std::shared_ptr<dealii::Triangulation<dim>> triangulation;
        // a distributed mesh starts serial on every process
        // (distribute_meshes())
        if (n_ranks > 1 && decomposition_.mesh_distribution ==
                             decomposition::DecompositionParameters::
                               MeshDistribution::replicated)
          triangulation =
            std::make_shared<dealii::parallel::shared::Triangulation<dim>>(
              MPI_COMM_WORLD,
              dealii::Triangulation<dim>::none,
              false,
              dealii::parallel::shared::Triangulation<dim>::partition_metis);
        else
          triangulation = std::make_shared<dealii::Triangulation<dim>>();
        parameters.mesh.create(*triangulation,
                               parameters.placement,
                               parameters.name);
        const unsigned int b          = triangulations_.size();
        bool               in_contact = false;
        for (const auto &pair : pair_parameters_)
          in_contact = in_contact || pair.involves_body(b);
        parameters.check_mesh(*triangulation, in_contact);
        details.push_back(
          parameters.name + ": " + parameters.mesh.description() + ", " +
          std::to_string(triangulation->n_active_cells()) + " cells" +
          (n_ranks > 1 && !has_distributed_meshes() ?
             ", METIS partition into " + std::to_string(n_ranks) +
               " subdomains" :
             ""));
        triangulations_.push_back(triangulation);
      }
      for (const auto &pair : pair_parameters_)
        pair.check_mesh(triangulations_);
      if (decomposition_.mesh_distribution ==
          decomposition::DecompositionParameters::MeshDistribution::distributed)
        distribute_meshes(details);
    }


    template <int dim>
    void
    Scene<dim>::distribute_meshes(std::vector<std::string> &details)
    {
      std::vector<std::string> names;
      for (const auto &parameters : body_parameters_)
        names.push_back(parameters.name);
      // the serial meshes go to DistributedMesh, which frees them
      std::vector<std::shared_ptr<dealii::Triangulation<dim>>> serial;
      serial.swap(triangulations_);
      distributed_mesh_ = std::make_unique<decomposition::DistributedMesh<dim>>(
        std::move(serial), names, fe_degree_, decomposition_, MPI_COMM_WORLD);
      std::ostringstream line;
      line << "distributed meshes (parallel::fullydistributed): "
           << distributed_mesh_->owners().size()
           << " subdomains, active cells per process";
      const std::vector<unsigned int> &cells =
        distributed_mesh_->cells_per_process();
      for (unsigned int p = 0; p < cells.size(); ++p)
        line << (p == 0 ? " " : ", ") << cells[p];
      details.push_back(line.str());
      for (unsigned int b = 0; b < body_parameters_.size(); ++b)
        triangulations_.push_back(distributed_mesh_->triangulation(b));
    }


    template <int dim>
    void
    Scene<dim>::setup(std::vector<std::string> &details)
    {
      bodies_.clear();
      for (unsigned int b = 0; b < body_parameters_.size(); ++b)
      {
        const BodyParameters<dim> &parameters = body_parameters_[b];
        auto                       body =
          std::make_unique<fem::ElasticBody<dim>>(parameters.name,
                                                  triangulations_[b],
                                                  fe_degree_,
                                                  parameters.materials,
                                                  curved_load_mapping_degree_);
        body->set_dirichlet_conditions(parameters.dirichlet);
        body->set_traction_conditions(parameters.tractions);
        if (parameters.has_body_force)
          body->set_body_force(parameters.body_force);
        body->set_load_time(load_time_);
        body->setup();
        std::string line =
          parameters.name + ": " + std::to_string(body->n_dofs()) + " dofs";
        // FE_Q is the scene line's; say so where it is not
        if (body->cell_family().is_simplex())
          line += " (" + body->fe().base_element(0).get_name() + " on " +
                  body->cell_family().cells_in_words() + ")";
        if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
        {
          const auto owned = dealii::Utilities::MPI::min_max_avg(
            body->dof_handler().n_locally_owned_dofs(), MPI_COMM_WORLD);
          line += " (" + std::to_string(static_cast<unsigned long>(owned.min)) +
                  " .. " +
                  std::to_string(static_cast<unsigned long>(owned.max)) +
                  " per process)";
        }
        const std::string solver_note = choose_solver(b, *body);
        details.push_back(line + solver_note);
        bodies_.push_back(std::move(body));
      }
    }


    template <int dim>
    std::string
    Scene<dim>::choose_solver(const unsigned int           b,
                              const fem::ElasticBody<dim> &body)
    {
      if (spread_solvers_.empty() || solvers_[b]->is_distributed())
        return "";
      const double megabytes =
        decomposition::DecompositionParameters::factor_megabytes_on_machine(
          dim, body.n_dofs(), false);
      if (megabytes <= factor_limit_)
        return "";
      std::swap(solvers_[b], spread_solvers_[b]);
      return ", stiffness solver mumps (cholmod's copies on the " +
             std::to_string(util::processes_on_this_machine()) +
             " processes of this machine: about " +
             std::to_string(std::llround(megabytes)) +
             " MB, above `Decomposition/Memory limit')";
    }


    template <int dim>
    void
    Scene<dim>::refine(std::vector<std::string> &details)
    {
      // the bodies' DoFHandlers must not outlive the meshes' old cells
      bodies_.clear();
      displacements_.clear();
      results_.clear();
      for (unsigned int b = 0; b < triangulations_.size(); ++b)
      {
        const unsigned int before = triangulations_[b]->n_active_cells();
        triangulations_[b]->execute_coarsening_and_refinement();
        details.push_back(body_parameters_[b].name + ": " +
                          std::to_string(before) + " -> " +
                          std::to_string(triangulations_[b]->n_active_cells()) +
                          " cells, finest level " +
                          std::to_string(triangulations_[b]->n_levels() - 1));
      }
    }


    template <int dim>
    void
    Scene<dim>::assemble(std::vector<std::string> &details,
                         const bool                global_systems)
    {
      if (!global_systems)
      {
        details.push_back("no global stiffness matrix: TFETI assembles "
                          "each subdomain's own (Factorization phase)");
        return;
      }
      for (auto &body : bodies_)
        body->assemble();
    }


    template <int dim>
    void
    Scene<dim>::set_load_time(const double time)
    {
      load_time_ = time;
      for (auto &body : bodies_)
        body->set_load_time(time);
    }


    template <int dim>
    void
    Scene<dim>::assemble_loads()
    {
      // TFETI assembles no body's K and f: its dual re-assembles the
      // subdomains' loads (decomposition::TFETIDual::update_load())
      for (auto &body : bodies_)
        if (body->is_assembled())
          body->assemble_load();
    }


    template <int dim>
    void
    Scene<dim>::solve(std::vector<std::string> &details, const bool factorize)
    {
      displacements_.resize(bodies_.size());
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        if (factorize)
          configure_solver(*solvers_[b], *bodies_[b]);
        bodies_[b]->solve(*solvers_[b], displacements_[b], factorize);
        const auto        &statistics = solvers_[b]->statistics();
        std::ostringstream line;
        line << std::setprecision(3) << bodies_[b]->name() << ": "
             << solvers_[b]->name() << ", setup " << statistics.setup_time
             << " s, solve " << statistics.solve_time << " s";
        if (statistics.factor_nonzeros > 0)
          line << ", factor nonzeros " << statistics.factor_nonzeros;
        if (statistics.iterations > 0)
          line << ", " << statistics.iterations << " iterations";
        details.push_back(line.str());
      }
    }


    template <int dim>
    void
    Scene<dim>::postprocess(
      const std::vector<dealii::Vector<double>> *contact_forces)
    {
      Assert(contact_forces == nullptr ||
               contact_forces->size() == bodies_.size(),
             dealii::ExcInternalError());
      results_.resize(bodies_.size());
      for (unsigned int b = 0; b < bodies_.size(); ++b)
        results_[b] = bodies_[b]->summarize(displacements_[b],
                                            contact_forces != nullptr ?
                                              &(*contact_forces)[b] :
                                              nullptr);
    }


    template void
    configure_solver<2>(fem::StiffnessSolver &, const fem::ElasticBody<2> &);
    template void
    configure_solver<3>(fem::StiffnessSolver &, const fem::ElasticBody<3> &);
    template <int dim>
    void
    Scene<dim>::set_solver_monitor(
      const std::function<void(const std::string &)> &monitor)
    {
      for (auto &solver : solvers_)
        solver->set_monitor(monitor);
    }


    template class Scene<2>;
    template class Scene<3>;
  } // namespace driver
} // namespace dualcontact
