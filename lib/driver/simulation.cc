#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <driver/results_report.h>
#include <driver/simulation.h>
#include <fem/rigid_body_modes.h>
#include <io/contact_surface_writer.h>
#include <io/parameter_file.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <regex>
#include <sstream>

namespace dualcontact
{
  namespace driver
  {
    namespace
    {
      /** "coulomb, mu = 0.3": a pair's law as its .prm names it. */
      std::string
      describe(const contact::FrictionLaw &law)
      {
        using Type = contact::FrictionLaw::Type;
        std::ostringstream text;
        text << std::setprecision(4);
        switch (law.type)
        {
          case Type::frictionless:
            text << "frictionless";
            break;
          case Type::tresca_isotropic:
            text << "tresca, slip bound " << law.first << " Pa";
            break;
          case Type::tresca_orthotropic:
            text << "tresca orthotropic, slip bounds " << law.first << ", "
                 << law.second << " Pa";
            break;
          case Type::coulomb_isotropic:
            text << "coulomb, friction coefficient " << law.first;
            break;
          case Type::coulomb_orthotropic:
            text << "coulomb orthotropic, friction coefficients " << law.first
                 << ", " << law.second;
            break;
        }
        return text.str();
      }
    } // namespace


    namespace
    {
      /**
       * The written files as the console lists them: a load history's
       * per-step files (`body_1_step_K.vtu', K = 1 .. n) as one item
       * `body_1_step_*.vtu (n steps)' at the place of the first, so that a
       * history of many steps keeps the line readable.
       */
      std::string
      list_file_names(const std::vector<std::string> &names)
      {
        static const std::regex  step_file("(.*_step_)[0-9]+(\\..*)");
        std::vector<std::string> items;
        std::map<std::string, unsigned int> steps_of_pattern;
        for (const auto &name : names)
        {
          std::smatch match;
          if (!std::regex_match(name, match, step_file))
          {
            items.push_back(name);
            continue;
          }
          const std::string pattern = match[1].str() + "*" + match[2].str();
          if (steps_of_pattern[pattern]++ == 0)
            items.push_back(pattern);
        }
        std::string list;
        for (const auto &item : items)
        {
          list += (list.empty() ? "" : ", ") + item;
          const auto pattern = steps_of_pattern.find(item);
          if (pattern != steps_of_pattern.end())
            list += " (" + std::to_string(pattern->second) + " steps)";
        }
        return list;
      }
    } // namespace


    namespace
    {
      OutputParameters
      read_output_parameters(dealii::ParameterHandler &prm)
      {
        OutputParameters output;
        output.parse_parameters(prm);
        return output;
      }
    } // namespace


    namespace
    {
      /**
       * The FCLIB export's refusal of a body that rigid-body motions move
       * (@p why): its K is singular, and the contact problem with the
       * equality constraints of SMALSE-M is not one FCLIB holds.
       */
      std::string
      fclib_floating_body_message(const std::string &body,
                                  const std::string &why)
      {
        return "The FCLIB export " +
               io::parameter_location("Output", "FCLIB problem") +
               " needs bodies held by Dirichlet conditions, but " + body + " " +
               why +
               ": its stiffness matrix is singular, and the contact problem "
               "(with rigid-body modes) is not an FCLIB problem. Hold the "
               "body, or set `FCLIB problem = none'.";
      }
    } // namespace


    template <int dim>
    void
    Simulation<dim>::check_fclib_bodies_held(const Scene<dim> &scene) const
    {
      for (unsigned int b = 0; b < scene.n_bodies(); ++b)
      {
        const unsigned int n_modes =
          fem::RigidBodyModes<dim>(scene.body(b)).n_modes();
        AssertThrow(n_modes == 0,
                    dealii::ExcMessage(fclib_floating_body_message(
                      scene.body(b).name(),
                      "has " + std::to_string(n_modes) +
                        (n_modes == 1 ? " rigid-body motion" :
                                        " rigid-body motions") +
                        " that its Dirichlet conditions do not hold")));
      }
    }


    template <int dim>
    Simulation<dim>::Simulation(dealii::ParameterHandler   &prm,
                                const std::string          &parameter_file,
                                dealii::ConditionalOStream &console,
                                io::ConsoleLog             *log)
        : prm_(prm)
        , parameter_file_(parameter_file)
        , console_(console)
        , run_log_(console, log)
        , is_output_rank_(
            dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        , timer_(console,
                 dealii::TimerOutput::never,
                 dealii::TimerOutput::wall_times)
        , output_(read_output_parameters(prm))
    {
      load_steps_.parse_parameters(prm);
      run_log_.set_parameters(output_);
      output_folder_ = std::make_unique<io::OutputFolder>(
        output_.folder, io::parameter_location("Output", "Output folder"));
      // one run per folder, taken before anything is computed
      if (is_output_rank_)
        output_folder_->lock();
      AssertThrow(output_.fclib_problem == "none" ||
                    dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) ==
                      1,
                  dealii::ExcMessage(
                    "FCLIB export runs on one process only: set it to none "
                    "under MPI. " +
                    io::parameter_location("Output", "FCLIB problem")));

      // before anything runs BLAS: the factorizations, the dense F
      blas_threads_ = fem::StiffnessSolver::apply_blas_threads(prm);
      scene_        = std::make_unique<Scene<dim>>(prm, parameter_file);
      // what FCLIB cannot hold is refused now, not after the solve: Tresca
      // or orthotropic friction, a floating body (K singular)
      if (output_.fclib_problem != "none" && scene_->has_contact())
      {
        for (const auto &pair : scene_->pair_parameters())
          AssertThrow(
            pair.pair.friction.type ==
                contact::FrictionLaw::Type::frictionless ||
              pair.pair.friction.type ==
                contact::FrictionLaw::Type::coulomb_isotropic,
            dealii::ExcMessage(
              "FCLIB export " +
              io::parameter_location("Output", "FCLIB problem") +
              ": contact pair `" + pair.pair.name +
              "' has Tresca or orthotropic friction; FCLIB problems hold "
              "isotropic Coulomb friction only (frictionless pairs are "
              "written with mu = 0)."));
        for (const auto &body : scene_->body_parameters())
          AssertThrow(!body.dirichlet.empty(),
                      dealii::ExcMessage(fclib_floating_body_message(
                        body.name, "has no Dirichlet condition")));
      }
      refinement_ = std::make_unique<ContactRefinement<dim>>(
        prm, scene_->pair_parameters().size());
      AssertThrow(!scene_->has_distributed_meshes() ||
                    refinement_->n_cycles() == 0,
                  dealii::ExcMessage(
                    "`subsection Contact refinement' refines the meshes "
                    "between solves, which a distributed mesh (`Mesh "
                    "distribution = distributed' in `subsection "
                    "Decomposition') does not support yet: use `Mesh "
                    "distribution = replicated' or no refinement cycles."));
      // scenes with contact go through a dual; so do scenes without
      // contact that ask for TFETI (then the dual has only gluing and
      // Dirichlet multipliers)
      prm.enter_subsection("Decomposition");
      const bool tfeti = prm.get("Method") == "tfeti";
      prm.leave_subsection();
      AssertThrow(!load_steps_.is_history() ||
                    prm.get("Contact solver") != "primal",
                  dealii::ExcMessage(
                    "A load history (more than one step in `subsection Load "
                    "steps') runs on the dual only: `set Contact solver = "
                    "dual'."));
      scene_->set_load_time(load_steps_.times.front());
      if (scene_->has_contact() || tfeti)
      {
        contact_ = std::make_unique<ContactStage<dim>>(prm, output_, *scene_);
        contact_->set_run_log(&run_log_);
      }
      scene_->set_solver_monitor(run_log_.monitor());
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
      run_log_.start_phase(name);
      {
        dealii::TimerOutput::Scope scope(timer_, name);
        phase();
      }
      timer.stop();
      run_log_.end_phase(name, timer.wall_time());
      for (const auto &detail : details_)
        console_ << "      " << detail << std::endl;
    }


    template <int dim>
    void
    Simulation<dim>::check_finite_results() const
    {
      const auto count_non_finite = [](const dealii::Vector<double> &values)
      {
        return static_cast<unsigned int>(
          std::count_if(values.begin(),
                        values.end(),
                        [](const double value)
                        { return !std::isfinite(value); }));
      };
      std::string what;
      for (unsigned int b = 0; b < scene_->n_bodies(); ++b)
      {
        const unsigned int n = count_non_finite(scene_->displacements()[b]);
        if (n > 0 || !std::isfinite(scene_->results()[b].strain_energy))
          what += (what.empty() ? "" : "; ") + scene_->body(b).name() + ": " +
                  std::to_string(n) + " of " +
                  std::to_string(scene_->displacements()[b].size()) +
                  " displacement values";
      }
      if (contact_)
      {
        const unsigned int n = count_non_finite(contact_->result().lambda);
        if (n > 0)
          what += (what.empty() ? "" : "; ") + std::string("the contact: ") +
                  std::to_string(n) + " of " +
                  std::to_string(contact_->result().lambda.size()) +
                  " multipliers";
        for (unsigned int p = 0; p < contact_->pair_results().size(); ++p)
          if (!std::isfinite(contact_->pair_results()[p].normal_force) ||
              !std::isfinite(contact_->pair_results()[p].max_pressure))
            what += (what.empty() ? "" : "; ") +
                    scene_->pair_parameters()[p].pair.name +
                    ": the normal force or pressure";
      }
      const bool any =
        dealii::Utilities::MPI::max(what.empty() ? 0 : 1, MPI_COMM_WORLD) > 0;
      AssertThrow(!any,
                  dealii::ExcMessage(
                    "The solution is not finite (NaN or inf" +
                    (what.empty() ? std::string(" on another process") :
                                    " in " + what) +
                    "): the scene's numbers overflow the range of doubles "
                    "(extreme Young's moduli, loads, displacements or "
                    "coordinates). Nothing was written."));
    }


    template <int dim>
    void
    Simulation<dim>::report_traction_resultants(const Scene<dim> &scene)
    {
      for (unsigned int b = 0; b < scene.n_bodies(); ++b)
      {
        const auto &resultants = scene.results()[b].traction_resultants;
        for (unsigned int t = 0; t < resultants.size(); ++t)
        {
          const auto        &r = resultants[t];
          std::ostringstream line;
          line << scene.body(b).name() << ", traction " << t + 1
               << " (boundary id " << r.boundary_id << "): resultant nominal "
               << std::setprecision(6) << r.nominal << ", applied " << r.applied
               << " (difference " << std::setprecision(2)
               << 100 * r.relative_difference() << " %)";
          details_.push_back(line.str());
          if (r.relative_difference() > traction_warning_threshold)
            details_.push_back(
              "Warning: the load of " + scene.body(b).name() + ", traction " +
              std::to_string(t + 1) +
              " differs from the load on the exact "
              "surface by more than " +
              std::to_string(100 * traction_warning_threshold).substr(0, 3) +
              " %: the loaded surface is not followed by the mesh (raise "
              "`Curved load mapping degree' or refine the mesh).");
        }
      }
    }


    template <int dim>
    void
    Simulation<dim>::report_force_balance(const Scene<dim> &scene)
    {
      for (unsigned int b = 0; b < scene.n_bodies(); ++b)
        if (const double imbalance = scene.results()[b].force_imbalance;
            !(imbalance <= force_balance_warning_threshold))
        {
          std::ostringstream line;
          line << std::setprecision(3) << "Warning: the forces on "
               << scene.body(b).name()
               << " do not balance: |applied + reactions + contact| is "
               << imbalance
               << " of the largest of them (a solver tolerance too loose "
                  "for the forces, or a solve that did not converge).";
          details_.push_back(line.str());
        }
    }


    template <int dim>
    void
    Simulation<dim>::print_scene_line()
    {
      const Scene<dim> &scene = *scene_;
      // solved through a dual (ContactStage), with or without contact pairs
      const bool         has_contact = contact_ != nullptr;
      const unsigned int n_pairs     = scene.pair_parameters().size();
      console_ << "Scene: " << dim << "D" << (dim == 2 ? " (plane strain)" : "")
               << ", " << scene.n_bodies() << " bod"
               << (scene.n_bodies() == 1 ? "y" : "ies") << ", FE_Q("
               << scene.fe_degree() << "), stiffness solver "
               << scene.solver(0).name();
      if (has_contact)
        console_ << ", " << n_pairs << " contact pair"
                 << (n_pairs == 1 ? "" : "s") << ", QP solver "
                 << contact_->qp_parameters().solver;
      console_ << ", BLAS threads " << blas_threads_ << std::endl;
    }


    template <int dim>
    void
    Simulation<dim>::validate()
    {
      Scene<dim> &scene = *scene_;
      print_scene_line();
      run_phase("Mesh", [&]() { scene.create_meshes(details_); });
      run_phase("Setup", [&]() { scene.setup(details_); });
      refinement_->check_meshes(scene);
      if (scene.has_contact() && output_.fclib_problem != "none")
        check_fclib_bodies_held(scene);

      console_ << "Bodies:" << std::endl;
      unsigned long n_cells = 0, n_dofs = 0;
      for (unsigned int b = 0; b < scene.n_bodies(); ++b)
      {
        const auto &body = scene.body(b);
        console_ << "  " << body.name() << ": "
                 << body.triangulation().n_global_active_cells() << " cells, "
                 << body.n_dofs() << " dofs, "
                 << scene.body_parameters()[b].mesh.description() << std::endl;
        n_cells += body.triangulation().n_global_active_cells();
        n_dofs += body.n_dofs();
      }
      console_ << "  total: " << n_cells << " cells, " << n_dofs << " dofs"
               << std::endl;
      if (scene.has_contact())
      {
        console_ << "Contact pairs:" << std::endl;
        for (const auto &p : scene.pair_parameters())
          console_ << "  " << p.pair.name << ": slave body "
                   << p.pair.slave_body + 1 << " boundary "
                   << p.pair.slave_boundary << ", master "
                   << p.master_description << ", " << describe(p.pair.friction)
                   << std::endl;
      }
      console_ << "Solvers: stiffness " << scene.solver(0).name();
      if (contact_ != nullptr)
        console_ << ", QP " << contact_->qp_parameters().solver << " to "
                 << contact_->qp_parameters().tolerance;
      console_ << std::endl
               << "The input is valid (nothing was computed or written)."
               << std::endl;
    }


    template <int dim>
    std::string
    Simulation<dim>::failure_message() const
    {
      std::ostringstream message;
      message << "The contact solver did NOT converge: "
              << contact_->result().reason << ".";
      if (!contact_->result().qp_statistics.empty())
      {
        const auto &last = contact_->result().qp_statistics.back();
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
      if (!contact_->result().coulomb_changes.empty())
        message << std::setprecision(3) << " Last Coulomb change of psi: "
                << contact_->result().coulomb_changes.back() << ".";
      if (load_steps_.is_history() && failed_step_ >= 0)
        message << std::setprecision(6) << " The load history stopped at step "
                << failed_step_ + 1 << " of " << load_steps_.times.size()
                << " (t = " << load_steps_.times[failed_step_]
                << "): the output is that step's.";
      message << " The output was written all the same, flagged as not "
                 "converged.";
      return message.str();
    }


    template <int dim>
    void
    Simulation<dim>::solve_step(const unsigned int step)
    {
      Scene<dim> &scene = *scene_;
      if (contact_ != nullptr)
      {
        run_phase("QP", [&]() { contact_->solve(details_); });
        run_phase("Recovery", [&]() { contact_->recover(details_); });
      }
      else
        run_phase("Solve", [&]() { scene.solve(details_, step == 0); });
      run_phase("Postprocessing",
                [&]()
                {
                  scene.postprocess(
                    contact_ ? &contact_->body_contact_forces() : nullptr);
                  report_traction_resultants(scene);
                  report_force_balance(scene);
                });
    }


    template <int dim>
    void
    Simulation<dim>::run_load_steps()
    {
      Scene<dim>        &scene   = *scene_;
      const unsigned int n_steps = load_steps_.times.size();
      failed_step_               = -1;
      // a refinement cycle computes the history again: its rows replace
      history_header_.clear();
      history_rows_.clear();
      pvd_series_.clear();
      for (unsigned int step = 0; step < n_steps; ++step)
      {
        const double time = load_steps_.times[step];
        if (step > 0)
          run_phase("Load step",
                    [&]()
                    {
                      scene.set_load_time(time);
                      scene.assemble_loads();
                      if (contact_ != nullptr)
                        contact_->start_load_step();
                    });
        if (load_steps_.is_history())
          console_ << "Load step " << step + 1 << " of " << n_steps
                   << ", t = " << time << std::endl;
        solve_step(step);
        if (load_steps_.is_history())
        {
          console_ << step_line(step) << std::endl;
          record_history_row(step);
          if (output_.write_vtu)
          {
            // every process writes its pieces of the step (collective)
            ResultsReport<dim> report(*scene_, contact_.get(), parameter_file_);
            report.write_output(*output_folder_,
                                true,
                                "_step_" + std::to_string(step + 1),
                                time,
                                &pvd_series_);
          }
        }
        if (contact_ != nullptr && !contact_->result().converged)
        {
          failed_step_ = step;
          break;
        }
      }
    }


    namespace
    {
      /**
       * Whether results.txt's key @p key goes into history.csv: a force
       * (not a traction's nominal one or a relative difference), a count,
       * an area or contact length, an energy (strain, external work,
       * dissipated), the largest displacement and pressure, and every
       * body's force imbalance (each step must balance).
       */
      bool
      is_history_key(const std::string &key)
      {
        const std::string last = key.substr(key.find_last_of('.') + 1);
        if (key.find("nominal") != std::string::npos ||
            key.find("relative") != std::string::npos ||
            key.rfind("contact.", 0) == 0 || key.rfind("refinement.", 0) == 0)
          return false;
        return key.find("force") != std::string::npos ||
               last.rfind("n_", 0) == 0 || last == "area" ||
               last == "contact_length" || last == "contact_area" ||
               last == "strain_energy" || last == "external_work" ||
               last == "dissipated_energy" || last == "max_displacement" ||
               last == "max_pressure" || last == "force_imbalance";
      }
    } // namespace


    template <int dim>
    void
    Simulation<dim>::record_history_row(const unsigned int step)
    {
      ResultsReport<dim> report(*scene_, contact_.get(), parameter_file_);
      report.set_dissipated_energy(true);
      std::vector<std::pair<std::string, std::string>> row;
      {
        std::ostringstream time;
        time << std::setprecision(12) << load_steps_.times[step];
        row.emplace_back("step", std::to_string(step + 1));
        row.emplace_back("time", time.str());
      }
      std::istringstream text(report.results_text());
      for (std::string line; std::getline(text, line);)
      {
        const auto equals = line.find('=');
        if (line.empty() || line[0] == '#' || equals == std::string::npos)
          continue;
        const std::string key = dealii::Utilities::trim(line.substr(0, equals));
        if (!is_history_key(key))
          continue;
        const std::vector<std::string> values =
          dealii::Utilities::split_string_list(line.substr(equals + 1), ',');
        if (values.size() == 1)
          row.emplace_back(key, values[0]);
        else
          for (unsigned int c = 0; c < values.size() && c < 3; ++c)
            row.emplace_back(key + "." + std::string(1, "xyz"[c]), values[c]);
      }
      if (history_header_.empty())
        for (const auto &[key, value] : row)
          history_header_.push_back(key);
      // in the header's columns (a key the first step did not have is left
      // out, one it had and this step has not is empty)
      std::vector<std::string> values(history_header_.size());
      for (const auto &[key, value] : row)
        for (unsigned int c = 0; c < history_header_.size(); ++c)
          if (history_header_[c] == key)
            values[c] = value;
      history_rows_.push_back(values);
    }


    template <int dim>
    std::string
    Simulation<dim>::step_line(const unsigned int step) const
    {
      std::ostringstream line;
      line << std::setprecision(6) << "  step " << step + 1 << " of "
           << load_steps_.times.size() << ", t = " << load_steps_.times[step];
      if (contact_ != nullptr)
      {
        unsigned int iterations = 0;
        for (const auto &q : contact_->result().qp_statistics)
          iterations += q.iterations;
        line << ": " << iterations << " QP iterations, "
             << contact_->result().qp_statistics.size() << " QP"
             << (contact_->result().qp_statistics.size() == 1 ? "" : "s");
        if (!contact_->result().coulomb_changes.empty())
          line << " (" << contact_->result().coulomb_changes.size()
               << " Coulomb iterates)";
        for (unsigned int p = 0; p < contact_->pair_results().size(); ++p)
        {
          const auto &r = contact_->pair_results()[p];
          line << "; " << scene_->pair_parameters()[p].pair.name << ": "
               << r.n_stick << " stick, " << r.n_slip << " slip, "
               << r.n_separated << " separated";
        }
        if (!contact_->result().converged)
          line << "; NOT CONVERGED";
      }
      return line.str();
    }


    template <int dim>
    bool
    Simulation<dim>::run()
    {
      Scene<dim> &scene = *scene_;
      // solved through a dual (ContactStage), with or without contact pairs
      const bool         has_contact = contact_ != nullptr;
      const unsigned int n_pairs     = scene.pair_parameters().size();
      print_scene_line();

      run_phase("Mesh", [&]() { scene.create_meshes(details_); });
      // Contact refinement: cycle 0 solves on the meshes as given, each
      // further cycle refines the contact zone of the previous solution and
      // solves again (the phase timings add up over the cycles)
      const unsigned int n_cycles = refinement_->n_cycles();
      for (unsigned int cycle = 0; cycle <= n_cycles; ++cycle)
      {
        dealii::Timer cycle_timer;
        if (cycle > 0)
        {
          console_ << "Refinement cycle " << cycle << " of " << n_cycles << " ("
                   << refinement_->description() << ")" << std::endl;
          run_phase("Refinement",
                    [&]()
                    {
                      refinement_->mark(scene, *contact_, cycles_.back());
                      details_.push_back(
                        std::to_string(cycles_.back().n_marked_cells) +
                        " cells marked");
                      contact_->reset();
                      scene.refine(details_);
                    });
        }
        // every cycle computes the whole history on its meshes
        scene.set_load_time(load_steps_.times.front());
        run_phase("Setup", [&]() { scene.setup(details_); });
        if (cycle == 0)
          refinement_->check_meshes(scene);
        if (cycle == 0 && has_contact && output_.fclib_problem != "none")
          check_fclib_bodies_held(scene);
        // TFETI needs no global K (FCLIB's export does: it writes the
        // undecomposed problem)
        run_phase("Assembly",
                  [&]()
                  {
                    scene.assemble(details_,
                                   !has_contact ||
                                     contact_->needs_global_systems() ||
                                     output_.fclib_problem != "none");
                  });
        if (has_contact)
        {
          ContactStage<dim> &contact = *contact_;
          run_phase("Contact search", [&]() { contact.discretize(details_); });
          run_phase("Factorization",
                    [&]() { contact.setup_dual_problem(details_); });
        }
        run_load_steps();
        if (n_cycles == 0)
          break;

        cycle_timer.stop();
        cycles_.push_back(refinement_->record(
          cycle, scene, *contact_, cycle_timer.wall_time()));
        const auto        &r = cycles_.back();
        std::ostringstream line;
        unsigned int       n_dofs = 0;
        for (const auto n : r.n_dofs)
          n_dofs += n;
        line << std::setprecision(4) << "  cycle " << cycle << ": " << n_dofs
             << " dofs, " << r.n_contact_nodes << " contact nodes ("
             << r.n_in_contact << " in contact), max pressure "
             << r.pair_max_pressure[0] << " Pa, " << r.wall_time << " s";
        console_ << line.str() << std::endl;
        if (!contact_->result().converged)
        {
          console_ << "  the contact solver did not converge: no further "
                      "refinement"
                   << std::endl;
          break;
        }
        if (refinement_->max_dofs() > 0 && n_dofs >= refinement_->max_dofs() &&
            cycle < n_cycles)
        {
          console_ << "  " << n_dofs << " dofs reach the `Maximum dofs' "
                   << refinement_->max_dofs() << ": no further refinement"
                   << std::endl;
          break;
        }
      }

      check_finite_results();
      console_ << "Results:" << std::endl;
      for (unsigned int b = 0; b < scene.n_bodies(); ++b)
      {
        std::ostringstream line;
        line << std::setprecision(6) << "  " << scene.body(b).name()
             << ": strain energy " << scene.results()[b].strain_energy
             << (dim == 2 ? " J/m" : " J") << ", max displacement "
             << scene.results()[b].max_displacement << " m";
        console_ << line.str() << std::endl;
      }
      for (unsigned int p = 0; has_contact && p < n_pairs; ++p)
      {
        const auto        &r = contact_->pair_results()[p];
        std::ostringstream line;
        line << std::setprecision(6) << "  "
             << scene.pair_parameters()[p].pair.name << ": normal force "
             << r.normal_force << (dim == 2 ? " N/m" : " N")
             << ", max pressure " << r.max_pressure << " Pa, " << r.n_nodes
             << " nodes: " << r.n_separated << " separated, " << r.n_stick
             << " stick, " << r.n_slip << " slip";
        console_ << line.str() << std::endl;
      }

      // every process writes its pieces (io::write_solution is collective);
      // process 0 also the master files and the records
      ResultsReport<dim> report(scene, contact_.get(), parameter_file_);
      report.set_refinement_cycles(&cycles_);
      report.set_dissipated_energy(load_steps_.is_history());
      run_phase("Output",
                [&]()
                {
                  if (!load_steps_.is_history() || !output_.write_vtu)
                    report.write_output(*output_folder_, output_.write_vtu);
                  else if (is_output_rank_)
                    // the steps' files are written: their series
                    output_folder_->write("solution.pvd",
                                          [&](std::ostream &out)
                                          { io::write_pvd(out, pvd_series_); });
                  if (has_contact && output_.fclib_problem != "none")
                    report.write_fclib_problem(*output_folder_,
                                               output_.fclib_problem);
                });
      // the records, then log.txt with everything the console showed up to
      // here (the list of files and the timing table included), then all
      // files renamed at once
      if (is_output_rank_)
      {
        report.write_records(*output_folder_, prm_, timer_);
        if (load_steps_.is_history())
          output_folder_->write(
            "history.csv",
            [&](std::ostream &out)
            {
              for (unsigned int c = 0; c < history_header_.size(); ++c)
                out << (c == 0 ? "" : ",") << history_header_[c];
              out << "\n";
              for (const auto &row : history_rows_)
              {
                for (unsigned int c = 0; c < row.size(); ++c)
                  out << (c == 0 ? "" : ",") << row[c];
                out << "\n";
              }
            });
      }

      const std::string failure = has_contact && !contact_->result().converged ?
                                    failure_message() :
                                    std::string();
      std::string       files   = list_file_names(output_folder_->file_names());
      if (is_output_rank_)
        files += ", log.txt";
      console_ << "Output written to `" << output_folder_->path()
               << "/': " << files;
      if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1 &&
          output_.write_vtu)
        console_ << ", and the other processes' pieces of the bodies";
      console_ << std::endl;
      if (output_.write_vtu)
        console_ << "Open `" << output_folder_->path()
                 << "/solution.pvd' in ParaView." << std::endl;
      timer_.print_summary();
      if (!failure.empty())
        run_log_.record("\nError: " + failure + "\n");
      if (is_output_rank_)
        output_folder_->write("log.txt",
                              [&](std::ostream &out)
                              { out << run_log_.text(); });
      output_folder_->commit();

      if (!failure.empty())
      {
        if (is_output_rank_)
          std::cerr << "\nError: " << failure << std::endl;
        return false;
      }
      return true;
    }


    template class Simulation<2>;
    template class Simulation<3>;
  } // namespace driver
} // namespace dualcontact
