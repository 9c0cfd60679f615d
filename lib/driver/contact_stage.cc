#include <deal.II/base/mpi.h>

#include <contact/contact_extent.h>
#include <contact/friction_capacity.h>
#include <driver/contact_stage.h>
#include <primal/uzawa_cgc.h>
#include <util/machine.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>

namespace dualcontact
{
  namespace driver
  {
    template <int dim>
    ContactStage<dim>::ContactStage(dealii::ParameterHandler &prm,
                                    const OutputParameters   &output,
                                    Scene<dim>               &scene)
        : prm_(prm)
        , scene_(scene)
        , write_coulomb_iterates_(output.write_coulomb_iterates)
        , status_tolerance_(output.contact_status_tolerance)
    {
      qp_parameters_.parse_parameters(prm);
      smalse_parameters_.parse_parameters(prm);
      coulomb_parameters_.parse_parameters(prm);
      dual_parameters_.parse_parameters(prm);
      working_set_parameters_.parse_parameters(prm);
      decomposition_parameters_.parse_parameters(prm);
      primal_parameters_.parse_parameters(prm);
      // a serial solver under MPI holds the whole factor on every process:
      // what `Memory limit' weighs is the machine's
      prm.enter_subsection("Stiffness solver");
      const std::string solver =
        fem::StiffnessSolver::resolved_name(prm.get("Solver"));
      prm.leave_subsection();
      solver_spreads_factor_ =
        fem::StiffnessSolver::spreads_over_processes(solver);
    }


    template <int dim>
    ContactStage<dim>::~ContactStage() = default;


    template <int dim>
    void
    ContactStage<dim>::discretize(std::vector<std::string> &details)
    {
      const std::vector<const fem::ElasticBody<dim> *> bodies = scene_.bodies();
      std::vector<contact::ContactPair<dim>>           pairs;
      for (const auto &parameters : scene_.pair_parameters())
        pairs.push_back(parameters.pair);
      contact_ =
        std::make_unique<contact::ContactDiscretization<dim>>(bodies, pairs);
      for (unsigned int p = 0; p < scene_.pair_parameters().size(); ++p)
      {
        // the slave surface's mesh size: its length (2D) or area (3D) per
        // contact node
        const auto &summary = contact_->pair_summaries()[p];
        if (summary.n_nodes > 0)
          scene_.pair_parameters()[p].check_initial_penetration(
            contact_->nodes(),
            p,
            std::pow(summary.area / summary.n_nodes, 1. / (dim - 1)));
      }
      for (unsigned int p = 0; p < scene_.pair_parameters().size(); ++p)
      {
        const auto        &summary = contact_->pair_summaries()[p];
        const auto        &pair    = scene_.pair_parameters()[p].pair;
        std::ostringstream line;
        line << std::setprecision(4) << summary.name << " (Body "
             << pair.slave_body + 1 << " boundary " << pair.slave_boundary
             << " on " << scene_.pair_parameters()[p].master_description;
        if (pair.obstacle)
          line << ": " << pair.obstacle->description();
        else
          line << " boundary " << pair.master_boundary;
        line << "): " << summary.n_nodes << " contact nodes, gap "
             << summary.min_gap << " .. " << summary.max_gap << " m, area "
             << summary.area << (dim == 2 ? " m" : " m^2");
        details.push_back(line.str());
      }
    }


    template <int dim>
    void
    ContactStage<dim>::setup_dual_problem(std::vector<std::string> &details)
    {
      const std::vector<const fem::ElasticBody<dim> *> bodies = scene_.bodies();
      dealii::ParameterHandler                        &prm    = prm_;
      if (method_choice_ != nullptr)
        details.push_back(method_choice_->description());
      if (decomposed())
      {
        decomposition::DecompositionParameters parameters =
          decomposition_parameters_;
        parameters.preconditioner = qp_parameters_.preconditioner;
        // `QP vectors = automatic': distributed on more than one process
        using Vectors = contact::DualProblemParameters::Vectors;
        parameters.distributed_multipliers =
          dual_parameters_.vectors == Vectors::distributed ||
          (dual_parameters_.vectors == Vectors::automatic &&
           dealii::Utilities::MPI::job_supports_mpi() &&
           dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1);
        dual_ = std::make_unique<decomposition::TFETIDual<dim>>(
          bodies,
          *contact_,
          parameters,
          [&prm, log = run_log_]()
          {
            auto solver = decomposition::make_subdomain_solver(prm);
            if (log != nullptr)
              solver->set_monitor(log->monitor());
            return solver;
          },
          MPI_COMM_WORLD,
          scene_.distributed_mesh());
        describe_decomposition(details);
      }
      else
        dual_ = std::make_unique<contact::DualProblem<dim>>(
          bodies,
          *contact_,
          // one solver per body, in body order (a fem::TrilinosSolver gets
          // the body's rows; a generalized inverse drops the fixing dofs
          // and with them this partition: the solver then splits evenly)
          [&prm, &bodies, b = 0u, log = run_log_]() mutable
          {
            auto solver = fem::StiffnessSolver::create(prm);
            if (log != nullptr)
              solver->set_monitor(log->monitor());
            if (b < bodies.size())
              configure_solver(*solver, *bodies[b++]);
            return solver;
          },
          dual_parameters_);
      std::ostringstream line;
      line << std::setprecision(4) << dual_->n_multipliers() << " multipliers ("
           << dual_->n_contact_nodes() << " normal, "
           << dual_->n_contact_multipliers() - dual_->n_contact_nodes()
           << " tangential";
      if (dual_->n_multipliers() > dual_->n_contact_multipliers())
        line << ", " << dual_->n_multipliers() - dual_->n_contact_multipliers()
             << " gluing and Dirichlet";
      line << "), " << dual_->n_rigid_body_modes()
           << " rigid-body modes, lambda_max(F) " << dual_->scale() << " m/N";
      details.push_back(line.str());
      details.push_back("Dual operator: " + dual_->operator_description());
      if (dual_->is_distributed())
      {
        std::ostringstream nodes;
        for (const unsigned int n : dual_->contact_nodes_per_process())
          nodes << (nodes.str().empty() ? "" : ", ") << n;
        details.push_back("Multipliers distributed by contact node: " +
                          nodes.str() + " nodes per process");
        // the working set selects rows of the whole multiplier vector
        // (ContactSolver::solve_on_working_set): said, not skipped silently
        if (working_set_parameters_.enabled && dual_->n_contact_nodes() > 0)
          details.push_back(
            "Working set (`subsection Dual problem/Working set'): not used, "
            "the QP runs on distributed vectors (`set QP vectors = "
            "replicated' uses it)");
      }
    }


    template <int dim>
    bool
    ContactStage<dim>::needs_global_systems() const
    {
      return primal_parameters_.contact_solver == "primal" || !decomposed();
    }


    template <int dim>
    bool
    ContactStage<dim>::decomposed() const
    {
      using Method = decomposition::DecompositionParameters::Method;
      if (decomposition_parameters_.method != Method::automatic)
        return decomposition_parameters_.method == Method::tfeti;
      // decided once per mesh (reset() forgets it), from the bodies as set
      // up: both estimates need their dofs
      if (method_choice_ == nullptr)
      {
        const bool mpi = dealii::Utilities::MPI::job_supports_mpi();
        method_choice_ = std::make_unique<decomposition::MethodChoice<dim>>(
          scene_.bodies(),
          decomposition_parameters_,
          qp_parameters_.tolerance,
          mpi ? dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) : 1,
          util::processes_on_this_machine(),
          solver_spreads_factor_);
      }
      return method_choice_->method() == Method::tfeti;
    }


    template <int dim>
    void
    ContactStage<dim>::describe_decomposition(
      std::vector<std::string> &details) const
    {
      const decomposition::TFETIDual<dim> &tfeti = *this->tfeti();
      std::ostringstream                   line;
      line << std::setprecision(4) << "Decomposition: TFETI, "
           << tfeti.n_subdomains() << " subdomains (";
      for (unsigned int b = 0; b < scene_.bodies().size(); ++b)
        line << (b == 0 ? "" : ", ") << scene_.bodies()[b]->name() << ": "
             << tfeti.n_subdomains_of_body(b);
      line << "), " << tfeti.n_primal_dofs()
           << " subdomain dofs (interface dofs once per subdomain), "
           << tfeti.n_multipliers() << " multipliers ("
           << tfeti.n_contact_multipliers() << " contact, "
           << tfeti.n_gluing_multipliers() << " gluing, "
           << tfeti.n_dirichlet_multipliers()
           << " Dirichlet), coarse problem G G' of order "
           << tfeti.n_rigid_body_modes() << " ("
           << tfeti.coarse_problem().n_nonzeros() << " nonzeros, sparse factor "
           << tfeti.coarse_problem().n_factor_nonzeros() << ", "
           << tfeti.coarse_problem().setup_time() << " s)";
      const std::vector<unsigned int> per_process =
        tfeti.subdomains_per_process();
      if (per_process.size() > 1)
      {
        const std::vector<unsigned int> dofs =
          tfeti.subdomain_dofs_per_process();
        line << "; subdomains (dofs) per process";
        for (unsigned int p = 0; p < per_process.size(); ++p)
          line << (p == 0 ? " " : ", ") << per_process[p] << " (" << dofs[p]
               << ")";
      }
      line << "; partition and assembly " << tfeti.decomposition_time()
           << " s, factorizations " << tfeti.stiffness_setup_time() << " s";
      if (tfeti.preconditioner_setup_time() > 0)
        line << ", preconditioner "
             << (tfeti.has_dirichlet_preconditioner() ? "(Dirichlet) " :
                                                        "(lumped) ")
             << tfeti.preconditioner_setup_time() << " s";
      details.push_back(line.str());
    }


    template <int dim>
    void
    ContactStage<dim>::start_load_step()
    {
      AssertThrow(primal_parameters_.contact_solver != "primal",
                  dealii::ExcMessage(
                    "Load steps run on the dual only: `set Contact solver "
                    "= dual' with `subsection Load steps'."));
      contact_->update_offsets(scene_.bodies());
      previous_slip_ = slip_;
      dual_->update_load(previous_slip_);
      warm_start_ = result_.lambda;
      // the iterates of this step only (written per step)
      coulomb_iterates_.clear();
    }


    template <int dim>
    void
    ContactStage<dim>::solve(std::vector<std::string> &details)
    {
      if (primal_parameters_.contact_solver == "primal")
      {
        AssertThrow(dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) ==
                      1,
                    dealii::ExcMessage(
                      "The primal Uzawa-CGC method runs on one "
                      "process only (`set Contact solver = dual' "
                      "under MPI)."));
        // the report's primal method on the same discretization; the dual
        // problem built before only serves the output (slip bounds, stick
        // and slip) and is not solved
        primal::UzawaCGC<dim> primal(scene_.bodies(),
                                     *contact_,
                                     primal_parameters_,
                                     coulomb_parameters_);
        const auto            r = primal.solve();
        result_.lambda          = r.lambda;
        result_.displacements   = r.displacements;
        result_.converged       = r.converged;
        result_.reason          = r.reason;
        dual_->set_slip_bounds(r.slip_bounds_first, r.slip_bounds_second);
        primal_json_  = r.to_json();
        qp_wall_time_ = r.cgc_time;
        std::ostringstream line;
        line << std::setprecision(3) << "Primal Uzawa-CGC (" << r.preconditioner
             << ", " << r.version << "): " << r.uzawa_iterations
             << " Uzawa iterations, " << r.n_tresca << " Tresca problem"
             << (r.n_tresca == 1 ? "" : "s") << ", " << r.n_cgc_solves
             << " CGC solves, " << r.total_inner_iterations
             << " CG steps; first CGC: " << r.first_outer.size()
             << " outer iterations, " << r.first_cgc.iterations
             << " CG steps; rho " << r.rho << ", " << r.total_time << " s";
        details.push_back(line.str());
        details.push_back((r.converged ? "" : "NOT CONVERGED: ") + r.reason);
        return;
      }
      qp::SolverParameters qp_parameters = qp_parameters_;
      if (run_log_ != nullptr)
        qp_parameters.progress = run_log_->qp_monitor();
      contact::ContactSolver<dim> solver(*dual_,
                                         qp_parameters,
                                         smalse_parameters_,
                                         coulomb_parameters_,
                                         working_set_parameters_);
      solver.set_final_recovery(false); // recover() does it, once
      if (warm_start_.size() > 0)
        solver.set_initial_multipliers(warm_start_);
      if (run_log_ != nullptr)
      {
        const auto start = std::chrono::steady_clock::now();
        solver.set_coulomb_monitor(
          [this, start](const auto &iterate)
          {
            const std::chrono::duration<double> elapsed =
              std::chrono::steady_clock::now() - start;
            run_log_->coulomb_iterate(iterate.coulomb_changes.size(),
                                      iterate.coulomb_changes.back(),
                                      coulomb_parameters_.tolerance,
                                      iterate.qp_statistics.empty() ?
                                        0 :
                                        iterate.qp_statistics.back().iterations,
                                      elapsed.count());
          });
      }
      std::function<void(const typename contact::ContactSolver<dim>::Result &)>
        on_iterate;
      if (write_coulomb_iterates_ && dual_->has_coulomb_friction())
        on_iterate = [this](const auto &iterate)
        {
          coulomb_iterates_.push_back(
            contact_surfaces(iterate.lambda, iterate.displacements));
        };
      result_ = solver.solve(on_iterate);
      if (!result_.converged)
        explain_failure();
      {
        std::ostringstream line;
        line << "QP vectors: " << result_.qp_vectors << ", multipliers per "
             << "process";
        for (unsigned int p = 0; p < result_.multipliers_per_process.size();
             ++p)
          line << (p == 0 ? " " : ", ") << result_.multipliers_per_process[p];
        details.push_back(line.str());
      }

      qp_wall_time_ = 0;
      for (unsigned int k = 0; k < result_.qp_statistics.size(); ++k)
      {
        const auto        &q = result_.qp_statistics[k];
        std::ostringstream line;
        line << std::setprecision(3) << "QP " << k + 1 << ": " << q.solver
             << ", " << qp::to_string(q.reason) << ", " << q.iterations
             << " iterations";
        if (q.n_outer > 0)
          line << " (" << q.n_outer << " SMALSE-M outer)";
        line << ", " << q.n_hessian_products << " Hessian products, "
             << q.wall_time << " s, criterion " << q.final_criterion;
        if (k < result_.coulomb_changes.size())
          line << ", Coulomb change of psi " << result_.coulomb_changes[k];
        details.push_back(line.str());
        if (k < result_.working_sets.size() && result_.working_sets[k].used)
        {
          const auto        &w = result_.working_sets[k];
          std::ostringstream set;
          set << std::setprecision(3) << "  working set: " << w.n_dropped
              << " of " << w.n_normal_rows
              << " normal rows left out (bound beyond the reach " << w.reach
              << " m), " << w.n_separated << " more found separated, "
              << w.n_added << " added back, " << w.n_rounds << " round"
              << (w.n_rounds == 1 ? "" : "s") << ", " << w.n_dropped_final
              << " checked free of penetration"
              << (w.fall_back.empty() ? "" : "; all rows: " + w.fall_back);
          details.push_back(set.str());
        }
        // solver auto: every attempt of the fall-back chain
        for (unsigned int a = 0; a < q.attempts.size(); ++a)
        {
          const auto        &t = q.attempts[a];
          std::ostringstream attempt;
          attempt << std::setprecision(3) << "  attempt " << a + 1 << ": "
                  << t.solver << ", " << qp::to_string(t.reason) << ", "
                  << t.iterations << " iterations, " << t.n_hessian_products
                  << " Hessian products, criterion " << t.final_criterion
                  << ", KKT stationarity " << t.kkt.stationarity
                  << ", feasibility " << t.kkt.feasibility
                  << (static_cast<int>(a) == q.chosen_attempt ?
                        " (returned)" :
                        " -> fall-back");
          details.push_back(attempt.str());
        }
        qp_wall_time_ += q.wall_time;
      }
      details.push_back(
        (result_.converged ? "" : "NOT CONVERGED: ") + result_.reason + ", " +
        std::to_string(dual_->n_stiffness_solves()) + " stiffness solves");
    }


    template <int dim>
    void
    ContactStage<dim>::explain_failure()
    {
      // a frictional QP of a floating body that cannot meet its force
      // balance inside the friction sets: say which load is too large
      if (!dual_->n_frictional_nodes())
        return;
      std::vector<typename contact::FrictionCapacity<dim>::Body> bodies;
      for (unsigned int b = 0; b < scene_.bodies().size(); ++b)
        bodies.push_back({scene_.bodies()[b]->name(),
                          scene_.bodies()[b]->applied_force(),
                          scene_.body_parameters()[b].dirichlet.empty()});
      const contact::FrictionCapacity<dim> capacity(*contact_, bodies);
      for (const std::string &finding : capacity.findings())
        result_.reason += ". " + finding;
    }


    template <int dim>
    void
    ContactStage<dim>::recover(std::vector<std::string> &details)
    {
      // the one recovery of the final multipliers (the contact solver's is
      // off); the primal method computes the displacements themselves
      if (primal_json_.empty())
      {
        if (!dual_->recover(result_.lambda,
                            scene_.displacements(),
                            result_.converged))
        {
          result_.reason += contact::undetermined_rigid_body_motion();
          details.push_back("Warning: the multipliers leave the rigid-body "
                            "motion of a floating body undetermined (set "
                            "to zero)");
        }
        if (tfeti() != nullptr)
        {
          std::ostringstream line;
          line << std::setprecision(3)
               << "Glued interfaces: largest jump between the copies of a "
                  "dof "
               << tfeti()->max_interface_jump() << " m ("
               << tfeti()->relative_interface_jump() << " of the largest |u|)";
          details.push_back(line.str());
        }
      }
      else
        scene_.displacements() = result_.displacements;
      surfaces_ = contact_surfaces(result_.lambda, scene_.displacements());
      // the slip of this step, and the work of friction on its increment
      slip_ = tangential_displacement(scene_.displacements());
      dissipated_energy_.resize(scene_.pair_parameters().size(), 0.);
      for (unsigned int i = 0; i < contact_->n_nodes(); ++i)
        if (const int j = dual_->frictional_index(i); j >= 0)
          for (unsigned int k = 0; k + 1 < dim; ++k)
          {
            const unsigned int t = (dim - 1) * i + k;
            const double       increment =
              slip_(t) - (previous_slip_.size() > 0 ? previous_slip_(t) : 0.);
            dissipated_energy_[contact_->nodes()[i].pair] +=
              result_.lambda(contact_->n_nodes() + (dim - 1) * j + k) *
              increment;
          }
      // the slave faces of every pair over its contact nodes (in the
      // pair's node order, as in surfaces_)
      surface_meshes_.clear();
      for (unsigned int p = 0; p < scene_.pair_parameters().size(); ++p)
      {
        const auto &pair = scene_.pair_parameters()[p].pair;
        std::vector<dealii::types::global_dof_index> node_dofs;
        for (const auto &node : contact_->nodes())
          if (node.pair == p)
            node_dofs.push_back(node.dofs[0]);
        surface_meshes_.emplace_back(scene_.body(pair.slave_body),
                                     pair.slave_boundary,
                                     node_dofs);
      }

      pair_results_.assign(scene_.pair_parameters().size(), PairResults());
      for (unsigned int p = 0; p < scene_.pair_parameters().size(); ++p)
      {
        PairResults &r       = pair_results_[p];
        const auto  &summary = contact_->pair_summaries()[p];
        r.min_gap            = summary.min_gap;
        r.max_gap            = summary.max_gap;
        r.area               = summary.area;
      }
      compute_contact_forces();
      const unsigned int n = contact_->n_nodes();
      for (unsigned int i = 0; i < n; ++i)
      {
        const auto  &node = contact_->nodes()[i];
        PairResults &r    = pair_results_[node.pair];
        r.normal_force += result_.lambda(i);
        const int j = dual_->frictional_index(i);
        if (j >= 0)
          for (unsigned int k = 0; k + 1 < dim; ++k)
            r.tangential_force +=
              result_.lambda(n + (dim - 1) * j + k) * node.tangents[k];
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
      // the contact zone with its edge between the nodes, from the pressure
      std::vector<std::vector<typename contact::ContactExtent<dim>::Node>>
        extent_nodes(surfaces_.size());
      for (unsigned int i = 0; i < n; ++i)
      {
        const auto &node = contact_->nodes()[i];
        const auto &surface =
          surfaces_[node.pair][extent_nodes[node.pair].size()];
        extent_nodes[node.pair].push_back(
          {node.dofs[0],
           node.position,
           surface.pressure,
           surface.status != io::contact_status::separated});
      }
      for (unsigned int p = 0; p < surfaces_.size(); ++p)
      {
        const auto &pair = scene_.pair_parameters()[p].pair;
        pair_results_[p].contact_measure =
          contact::ContactExtent<dim>(scene_.body(pair.slave_body),
                                      pair.slave_boundary,
                                      extent_nodes[p])
            .measure();
      }
    }


    template <int dim>
    void
    ContactStage<dim>::compute_contact_forces()
    {
      const unsigned int n = contact_->n_nodes();
      // the multipliers of each pair alone, lambda_T at every node (zero at
      // a frictionless one)
      std::vector<dealii::Vector<double>> normal(
        scene_.pair_parameters().size(), dealii::Vector<double>(n));
      std::vector<dealii::Vector<double>> tangential(
        scene_.pair_parameters().size(), dealii::Vector<double>((dim - 1) * n));
      for (unsigned int i = 0; i < n; ++i)
      {
        const unsigned int p = contact_->nodes()[i].pair;
        normal[p](i)         = result_.lambda(i);
        const int j          = dual_->frictional_index(i);
        if (j >= 0)
          for (unsigned int k = 0; k + 1 < dim; ++k)
            tangential[p]((dim - 1) * i + k) =
              result_.lambda(n + (dim - 1) * j + k);
      }
      body_contact_forces_.assign(scene_.n_bodies(), dealii::Vector<double>());
      for (unsigned int b = 0; b < scene_.n_bodies(); ++b)
        body_contact_forces_[b].reinit(scene_.body(b).n_dofs());
      for (unsigned int p = 0; p < normal.size(); ++p)
      {
        const dealii::Vector<double> forces =
          contact_->nodal_contact_forces(normal[p], tangential[p]);
        for (unsigned int b = 0; b < scene_.n_bodies(); ++b)
          for (dealii::types::global_dof_index i = 0;
               i < body_contact_forces_[b].size();
               ++i)
            body_contact_forces_[b](i) += forces(contact_->body_offset(b) + i);
        // the force on the slave's nodes, by component through the nodes'
        // dofs (a slave row touches its own node only): the pair's force
        // on the master is its opposite
        const unsigned int slave = scene_.pair_parameters()[p].pair.slave_body;
        dealii::Tensor<1, dim> on_slave;
        for (const auto &node : contact_->nodes())
          if (node.pair == p)
            for (unsigned int c = 0; c < dim; ++c)
              on_slave[c] +=
                forces(contact_->body_offset(slave) + node.dofs[c]);
        pair_results_[p].contact_force = -on_slave;
      }
    }


    template <int dim>
    void
    ContactStage<dim>::reset()
    {
      dual_.reset();
      contact_.reset();
      method_choice_.reset();
      result_       = typename contact::ContactSolver<dim>::Result();
      primal_json_  = "";
      qp_wall_time_ = 0;
      surfaces_.clear();
      surface_meshes_.clear();
      coulomb_iterates_.clear();
      pair_results_.clear();
      body_contact_forces_.clear();
      slip_.reinit(0);
      previous_slip_.reinit(0);
      warm_start_.reinit(0);
      dissipated_energy_.clear();
    }


    template <int dim>
    dealii::Vector<double>
    ContactStage<dim>::tangential_displacement(
      const std::vector<dealii::Vector<double>> &displacements) const
    {
      dealii::Vector<double> u(contact_->n_dofs());
      for (unsigned int b = 0; b < displacements.size(); ++b)
        for (unsigned int k = 0; k < displacements[b].size(); ++k)
          u(contact_->body_offset(b) + k) = displacements[b](k);
      dealii::Vector<double> bt((dim - 1) * contact_->n_nodes());
      contact_->tangential_matrix().vmult(bt, u);
      bt += contact_->tangential_offset();
      return bt;
    }


    template <int dim>
    typename ContactStage<dim>::Surfaces
    ContactStage<dim>::contact_surfaces(
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

      std::vector<double> max_lambda(scene_.pair_parameters().size(), 0.);
      for (unsigned int i = 0; i < n; ++i)
        max_lambda[contact_->nodes()[i].pair] =
          std::max(max_lambda[contact_->nodes()[i].pair], lambda(i));

      const auto &psi_first  = dual_->slip_bounds_first();
      const auto &psi_second = dual_->slip_bounds_second();
      std::vector<std::vector<io::ContactSurfaceNode<dim>>> surfaces(
        scene_.pair_parameters().size());
      for (unsigned int i = 0; i < n; ++i)
      {
        const auto                 &node = contact_->nodes()[i];
        const contact::FrictionLaw &law =
          scene_.pair_parameters()[node.pair].pair.friction;
        io::ContactSurfaceNode<dim> out;
        out.position = node.position;
        out.normal   = node.normal;
        out.pressure = lambda(i) / node.weight;
        out.weight   = node.weight;
        out.gap      = c(i) - bn(i);
        for (unsigned int k = 0; k + 1 < dim; ++k)
        {
          const unsigned int t = (dim - 1) * i + k;
          out.slip += bt(t) * node.tangents[k];
          out.slip_increment +=
            (bt(t) - (previous_slip_.size() > 0 ? previous_slip_(t) : 0.)) *
            node.tangents[k];
        }

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


    template class ContactStage<2>;
    template class ContactStage<3>;
  } // namespace driver
} // namespace dualcontact
