#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <contact/contact_solver.h>
#include <fclib/accuracy.h>
#include <fclib/fclib_file.h>
#include <fclib/local_solver.h>
#include <fclib/newton_solver.h>
#include <io/parameter_file.h>
#include <qp/solver_factory.h>
#include <qp/solver_parameters.h>
#include <tools/command_line.h>
#include <tools/fclibsolve_driver.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <optional>

namespace dualcontact
{
  namespace tools
  {
    using namespace fclib;

    namespace
    {
      /** A positive finite number (a tolerance). */
      double
      to_positive_number(const std::string &option, const std::string &v)
      {
        const double x = parse_number(option, v);
        if (!(x > 0))
          throw UsageError(option + " must be > 0 (got " + v + ")");
        return x;
      }

      /** An iteration limit: an integer in [1, 2^31). */
      long
      to_iteration_limit(const std::string &option, const std::string &v)
      {
        const long value = parse_integer(option, v);
        if (value < 1 || value > std::numeric_limits<int>::max())
          throw UsageError(option + " must be an integer in [1, " +
                           std::to_string(std::numeric_limits<int>::max()) +
                           "] (got " + v + ")");
        return value;
      }


      void
      declare(dealii::ParameterHandler &prm)
      {
        LocalSolver::Parameters::declare_parameters(prm);
        prm.declare_entry("Storage of W",
                          "auto",
                          dealii::Patterns::Selection(storage_names.choices()),
                          "How W is kept for its products: dense (BLAS "
                          "dsymv/dgemv, column-major), sparse, or auto "
                          "(dense when at least a quarter of the entries are "
                          "non-zero).");
        qp::SolverParameters::declare_parameters(prm);
        // friction needs disc blocks, which mprgp (the scenes' default)
        // does not take
        prm.enter_subsection("QP solver");
        prm.set("Solver", "mpgp");
        prm.leave_subsection();
        contact::CoulombParameters::declare_parameters(prm);
      }

      /** The command line, checked: every option given is set. */
      struct Options
      {
        bool        help = false;
        std::string file, prm_file, json_file, write_file, model_name, solver,
          first_name, storage_name, prox;
        bool fixed_rho = false, exact_qps = false, info_only = false;
        // unset unless given: every given value is checked (no sentinel
        // that a user could write, such as -1, is taken for "the default")
        std::optional<double>    tol, coulomb_tol;
        std::optional<long>      max_iter, coulomb_max_iter;
        std::vector<std::string> settings;
      };


      /** The options of @p args; throws UsageError naming a bad one. */
      Options
      parse_options(const std::vector<std::string> &args)
      {
        Options o;
        for (std::size_t i = 0; i < args.size(); ++i)
        {
          const std::string &a     = args[i];
          auto               value = [&]() -> std::string
          {
            if (i + 1 >= args.size())
              throw UsageError("option " + a + " needs a value");
            return args[++i];
          };
          if (a == "--help" || a == "-h")
          {
            o.help = true;
            return o;
          }
          else if (a == "--prm")
            o.prm_file = value();
          else if (a == "--set")
            o.settings.push_back(value());
          else if (a == "--model")
            o.model_name = value();
          else if (a == "--prox")
            o.prox = value();
          else if (a == "--fixed-rho")
            o.fixed_rho = true;
          else if (a == "--exact-qps")
            o.exact_qps = true;
          else if (a == "--first")
            o.first_name = value();
          else if (a == "--storage")
            o.storage_name = value();
          else if (a == "--solver")
            o.solver = value();
          else if (a == "--tol")
            o.tol = to_positive_number(a, value());
          else if (a == "--coulomb-tol")
            o.coulomb_tol = to_positive_number(a, value());
          else if (a == "--max-iter")
            o.max_iter = to_iteration_limit(a, value());
          else if (a == "--coulomb-max-iter")
            o.coulomb_max_iter = to_iteration_limit(a, value());
          else if (a == "--json")
            o.json_file = value();
          else if (a == "--write")
            o.write_file = value();
          else if (a == "--info")
            o.info_only = true;
          else if (!a.empty() && a[0] == '-')
            throw UsageError("unknown option " + a);
          else if (o.file.empty())
            o.file = a;
          else
            throw UsageError("more than one problem file given (" + o.file +
                             ", " + a + ")");
        }
        if (o.file.empty())
          throw UsageError("no FCLIB file given");
        return o;
      }


      /** What the solve runs with: the .prm, then --set, then the options. */
      struct Settings
      {
        qp::SolverParameters       qp;
        contact::CoulombParameters coulomb;
        LocalSolver::Parameters    loop;
        Storage                    storage = Storage::automatic;
      };


      /** The settings of @p o, checked (throws naming the parameter). */
      Settings
      read_settings(const Options &o)
      {
        dealii::ParameterHandler prm;
        declare(prm);
        if (!o.prm_file.empty())
          io::parse_parameter_file(prm, o.prm_file, false);
        std::vector<io::ParameterOverride> overrides;
        for (const auto &setting : o.settings)
          overrides.push_back(io::parse_parameter_override(setting));
        io::apply_parameter_overrides(prm, overrides, false);
        Settings settings;
        settings.qp.parse_parameters(prm);
        settings.coulomb.parse_parameters(prm);
        LocalSolver::Parameters &loop = settings.loop;
        loop.parse_parameters(prm);
        if (!o.model_name.empty())
          loop.model = model_names.value(o.model_name);
        if (!o.first_name.empty())
          loop.first = first_iterate_names.value(o.first_name);
        if (!o.prox.empty())
          loop.parse_proximal(o.prox);
        if (o.fixed_rho)
          loop.adaptive_rho = false;
        if (o.exact_qps)
          loop.inexact = false;
        loop.check();
        if (!o.solver.empty())
        {
          qp::create<dealii::Vector<double>>(o.solver, settings.qp); // checks
          settings.qp.solver = o.solver;
        }
        if (o.tol)
          settings.qp.tolerance = *o.tol;
        // model newton stops on the FCLIB error at the QPs' tolerance
        settings.loop.newton.tolerance = settings.qp.tolerance;
        settings.loop.newton.check();
        if (o.max_iter)
          settings.qp.max_iterations = *o.max_iter;
        if (o.coulomb_tol)
          settings.coulomb.tolerance = *o.coulomb_tol;
        else if (o.tol && settings.coulomb.tolerance ==
                            contact::CoulombParameters().tolerance)
          // --tol alone asks for that accuracy: the Coulomb loop follows
          // (its change of psi cannot be measured below the QPs' noise: with
          // QP tolerance 1e-4 and the Coulomb default 1e-6, Capsules ran
          // 1000 proximal iterations without converging; doc/fclib.md)
          settings.coulomb.tolerance = *o.tol;
        if (o.coulomb_max_iter)
          settings.coulomb.max_iterations = *o.coulomb_max_iter;
        settings.qp.check();
        settings.storage = storage_names.value(prm.get("Storage of W"));
        if (!o.storage_name.empty())
          settings.storage = storage_names.value(o.storage_name);
        return settings;
      }


      /** The local problem of @p file (a global one reduced to local form),
       *  with its sizes printed and put in @p summary. */
      LocalProblem
      read_problem(const std::string &file,
                   const Storage      storage,
                   std::ostream      &out,
                   nlohmann::json    &summary)
      {
        dealii::Timer reading;
        const Form    form = form_of(file);
        summary["file"]    = file;
        summary["form"]    = to_string(form);
        LocalProblem problem;
        if (form == Form::local)
          problem = read_local(file, storage);
        else
        {
          const GlobalProblem global = read_global(file);
          out << "global problem: " << global.n_dofs() << " dofs, "
              << global.n_contacts() << " contacts"
              << (global.M_was_upper_triangle() ?
                    " (M stored as its upper triangle)" :
                    "")
              << "\n";
          summary["n_dofs"] = global.n_dofs();
          problem           = global.reduce_to_local(storage);
          out << "reduced to local form with " << global.factorization_name()
              << "\n";
          summary["factorization"] = global.factorization_name();
        }
        const auto [mu_min, mu_max] =
          std::minmax_element(problem.mu().begin(), problem.mu().end());
        out << "local problem: " << problem.n_contacts() << " contacts, "
            << problem.size() << " unknowns, dimension " << problem.spacedim()
            << ", mu in [" << (problem.n_contacts() ? *mu_min : 0.) << ", "
            << (problem.n_contacts() ? *mu_max : 0.)
            << "], nnz(W) = " << problem.delassus().n_nonzero() << " ("
            << (problem.delassus().dense() ? "dense" : "sparse") << " storage)"
            << ", asymmetry of W " << problem.delassus().asymmetry()
            << ", read in " << reading.wall_time() << " s\n";
        summary["n_contacts"] = problem.n_contacts();
        summary["spacedim"]   = problem.spacedim();
        summary["storage"]    = problem.delassus().dense() ? "dense" : "sparse";
        summary["asymmetry_W"] = problem.delassus().asymmetry();
        summary["read_time_s"] = reading.wall_time();
        return problem;
      }


      /** --info: the rank of W and the spread of its normal diagonal. */
      void
      print_info(const LocalProblem &problem,
                 std::ostream       &out,
                 nlohmann::json     &summary)
      {
        const int rank = problem.delassus().numerical_rank(1e-10);
        out << "rank of W_s (pivots above 1e-10 max diag) " << rank
            << ", zero rows of W " << problem.delassus().n_zero_rows() << "\n";
        // spread of the normal diagonal entries W_nn over the contacts
        // (how much a per-contact scaling could change the conditioning)
        double       diag_min = 0, diag_max = 0;
        const auto  &W = problem.delassus().matrix();
        const double d = problem.spacedim();
        for (unsigned int i = 0; i < problem.n_contacts(); ++i)
        {
          const double w = W.el(d * i, d * i);
          diag_min       = i == 0 ? w : std::min(diag_min, w);
          diag_max       = i == 0 ? w : std::max(diag_max, w);
        }
        out << "normal diagonal entries of W in [" << diag_min << ", "
            << diag_max << "]\n";
        summary["normal_diagonal_W"] = {diag_min, diag_max};
        summary["rank_W"]            = rank;
        summary["zero_rows_W"]       = problem.delassus().n_zero_rows();
      }


      /** The outcome of the loop, printed. */
      void
      print_result(const LocalSolver::Result &result,
                   const Settings            &settings,
                   std::ostream              &out)
      {
        const auto &last  = result.qp_statistics.back();
        const Model model = settings.loop.model;
        out << "model " << model_names.name(model)
            << (model == Model::coulomb_fixed_point ?
                  std::string(" (first iterate ") +
                    first_iterate_names.name(settings.loop.first) + ")" :
                  "")
            << ", QP solver " << settings.qp.solver << " (tolerance "
            << settings.qp.tolerance << ")\n";
        out << std::setprecision(6);
        out << (result.converged ? "converged" : "NOT converged") << ": "
            << result.reason << "\n"
            << "  QPs " << result.qp_statistics.size() << ", QP iterations "
            << result.iterations << ", products with W "
            << result.hessian_products << ", time " << result.wall_time
            << " s\n"
            << "  last QP: criterion " << last.final_criterion
            << " (relative), KKT stationarity " << last.kkt.stationarity
            << "\n";
        out << "  proximal point " << result.proximal_reason;
        if (!result.rhos.empty())
          out << ", rho / lambda_max first " << settings.loop.rho << ", last "
              << result.rhos.back() << ", range ["
              << *std::min_element(result.rhos.begin(), result.rhos.end())
              << ", "
              << *std::max_element(result.rhos.begin(), result.rhos.end())
              << "]";
        out << "\n";
        if (!result.perturbations.empty())
          out << "  last perturbation of q ||rho dr + W_a dr|| / ||q|| "
              << result.perturbations.back() << "\n";
        if (result.newton.steps > 0)
          out << "  Newton method after the plain loop: "
              << (result.newton.converged ? "converged" : "failed") << " in "
              << result.newton.steps << " steps ("
              << result.newton.proximal_iterations << " proximal problems, "
              << result.newton.products << " products with W, "
              << result.newton.wall_time << " s)\n";
        if (result.polish_steps > 0 || result.polish_qps > 0)
          out << "  polish to the FCLIB error: "
              << (result.polish_qps > 0 ?
                    std::to_string(result.polish_qps) + " tighter QPs" :
                    std::to_string(result.polish_steps) + " Newton steps")
              << "\n";
        if (!result.coulomb_changes.empty())
          out << "  Coulomb iterations " << result.coulomb_changes.size()
              << ", last relative change of psi "
              << result.coulomb_changes.back() << "\n";
        out << "  FCLIB error " << std::scientific << result.fclib_error
            << std::defaultfloat << "\n";
      }


      /** A file written with its solution (e.g. by a dualcontact scene): how
       *  far is the stored r, and how far is ours from it. */
      void
      compare_with_stored_solution(const std::string            &file,
                                   const LocalProblem           &problem,
                                   const dealii::Vector<double> &r,
                                   std::ostream                 &out,
                                   nlohmann::json               &summary)
      {
        const dealii::Vector<double> stored = read_solution_r(file);
        if (stored.size() != r.size() || !(stored.l2_norm() > 0))
          return;
        dealii::Vector<double> difference(r);
        difference -= stored;
        const double error_stored = fclib_error(problem, stored);
        const double relative     = difference.l2_norm() / stored.l2_norm();
        out << "  stored solution: FCLIB error " << std::scientific
            << error_stored << ", ||r - r_stored|| / ||r_stored|| " << relative
            << std::defaultfloat << "\n";
        summary["stored_solution_fclib_error"] = error_stored;
        summary["difference_to_stored"]        = relative;
      }


      /** The outcome of the loop in the JSON summary. */
      void
      add_result(const LocalSolver::Result &result,
                 const Settings            &settings,
                 nlohmann::json            &summary)
      {
        summary["model"] = model_names.name(settings.loop.model);
        summary["first_iterate"] =
          first_iterate_names.name(settings.loop.first);
        summary["proximal"]         = result.proximal;
        summary["proximal_reason"]  = result.proximal_reason;
        summary["rhos"]             = result.rhos;
        summary["perturbations"]    = result.perturbations;
        summary["inexact"]          = settings.loop.inexact;
        summary["solver"]           = settings.qp.solver;
        summary["tolerance"]        = settings.qp.tolerance;
        summary["converged"]        = result.converged;
        summary["reason"]           = result.reason;
        summary["n_qp"]             = result.qp_statistics.size();
        summary["iterations"]       = result.iterations;
        summary["hessian_products"] = result.hessian_products;
        summary["power_products"]   = result.power_products;
        summary["time_s"]           = result.wall_time;
        summary["coulomb_changes"]  = result.coulomb_changes;
        summary["fclib_error"]      = result.fclib_error;
        summary["last_qp"]      = result.qp_statistics.back().to_json(false);
        summary["newton_steps"] = result.newton.steps;
        summary["newton_converged"] = result.newton.converged;
        summary["newton_time_s"]    = result.newton.wall_time;
        summary["polish_steps"]     = result.polish_steps;
        summary["polish_qps"]       = result.polish_qps;
        // (--tol alone sets it too)
        summary["coulomb_tolerance"] = settings.coulomb.tolerance;
        // per QP of the loop: iterations, products, tolerance, criterion
        nlohmann::json qps = nlohmann::json::array();
        for (const auto &s : result.qp_statistics)
          qps.push_back({s.iterations,
                         s.n_hessian_products,
                         s.tolerance,
                         s.final_criterion});
        summary["qps"] = qps;
      }


      /** The outcome of model newton, printed. */
      void
      print_newton_result(const NewtonSolver::Result &result,
                          const Settings             &settings,
                          std::ostream               &out)
      {
        out << "model newton (Alart-Curnier, proximal point), tolerance "
            << settings.loop.newton.tolerance << " on the FCLIB error\n";
        out << std::setprecision(6);
        out << (result.converged ? "converged" : "NOT converged") << ": "
            << result.reason << "\n"
            << "  Newton steps " << result.steps << " (plain "
            << result.plain_steps << "), proximal problems "
            << result.proximal_iterations << ", products with W "
            << result.products << ", step halvings " << result.halvings
            << ", time " << result.wall_time << " s\n";
        if (!result.sigmas.empty())
          out << "  sigma / mean W_nn first " << result.sigmas.front()
              << ", last " << result.sigmas.back() << "\n";
        out << "  FCLIB error " << std::scientific << result.fclib_error
            << std::defaultfloat << "\n";
      }


      /** The outcome of model newton in the JSON summary (the keys of
       *  add_result() where they mean the same). */
      void
      add_newton_result(const NewtonSolver::Result &result,
                        const Settings             &settings,
                        nlohmann::json             &summary)
      {
        summary["model"]               = "newton";
        summary["tolerance"]           = settings.loop.newton.tolerance;
        summary["converged"]           = result.converged;
        summary["reason"]              = result.reason;
        summary["newton_steps"]        = result.steps;
        summary["newton_plain_steps"]  = result.plain_steps;
        summary["proximal"]            = result.proximal_iterations > 0;
        summary["proximal_iterations"] = result.proximal_iterations;
        summary["sigmas"]              = result.sigmas;
        summary["errors"]              = result.errors;
        summary["halvings"]            = result.halvings;
        summary["n_qp"]                = 0;
        summary["iterations"]          = result.steps;
        summary["hessian_products"]    = result.products;
        summary["time_s"]              = result.wall_time;
        summary["fclib_error"]         = result.fclib_error;
      }


      /** --json FILE: the summary. */
      void
      write_summary(const std::string &json_file, const nlohmann::json &summary)
      {
        std::ofstream json(json_file);
        AssertThrow(json.good(),
                    dealii::ExcMessage("Cannot write `" + json_file + "'"));
        json << summary.dump(2) << "\n";
      }


      /**
       * Runs @p action (reading or solving the problem of @p file): an error
       * whose message does not name the file is rethrown with "FCLIB file
       * `FILE'" and @p what in front.  A damaged file can hold values that
       * the reader takes (finite, but 1e300) and that fail later, in the
       * reduction to local form or in the solver, whose messages know no
       * file.
       */
      template <typename Action>
      auto
      naming_file(const std::string &file,
                  const std::string &what,
                  const Action      &action) -> decltype(action())
      {
        try
        {
          return action();
        }
        catch (const dealii::ExceptionBase &e)
        {
          const std::string message = exception_message(e);
          if (message.find(file) != std::string::npos)
            throw;
          AssertThrow(false,
                      dealii::ExcMessage("FCLIB file `" + file + "'" + what +
                                         ": " + message));
        }
        std::abort(); // not reached
      }
    } // namespace


    std::string
    FclibSolveDriver::usage()
    {
      return "Usage: fclibsolve FILE.hdf5 [options]\n"
             "Solve an FCLIB frictional contact problem (local, or global "
             "reduced to W = H'M^-1 H,\n"
             "q = H'M^-1 f + w) with dualcontact's QP solvers, and report the "
             "FCLIB accuracy\n"
             "||r - P_K(r - u - mu||u_t|| e_n)|| / max(||q||, ||r||, ||u||), "
             "u = W r + q.\n"
             "Options (they override a .prm):\n"
             "  --prm FILE.prm        parameters: Model, subsections `QP "
             "solver', `Coulomb' and\n"
             "                        `Newton'\n"
             "  --set \"Subsection/Entry=value\"  one parameter of them, "
             "after the .prm (repeatable;\n"
             "                        e.g. --set \"Coulomb/Tolerance=1e-6\", "
             "--set \"QP solver/Solver=mpgp-bb\")\n"
             "  --model coulomb|cone|desaxce|newton  Coulomb fixed point "
             "over Tresca QPs\n"
             "                        (default), the cone QP (a convex "
             "relaxation, 3D only), the\n"
             "                        fixed point of De Saxce's shift over "
             "cone QPs (exact, 3D\n"
             "                        only), or the semismooth Newton method "
             "on Alart-Curnier's\n"
             "                        equations in a proximal loop (no QPs; "
             "stops on the FCLIB\n"
             "                        error <= --tol; subsection `Newton')\n"
             "  --first bonded|frictionless  first Coulomb iterate (default "
             "bonded)\n"
             "  --prox off|on|auto|RHO  proximal point, rho/2 ||r - "
             "r_previous||^2 (singular W;\n"
             "                        default auto: the plain loop; if it "
             "fails, the Newton method\n"
             "                        (model newton), and the proximal loop "
             "if that fails too;\n"
             "                        RHO: on, initial rho relative to "
             "lambda_max)\n"
             "  --fixed-rho           do not adapt rho\n"
             "  --exact-qps           every QP to the QP tolerance (no "
             "inexact fixed point)\n"
             "  --storage auto|dense|sparse  how W is kept for the products "
             "(default auto: dense\n"
             "                        from 1/4 non-zero entries)\n"
             "  --solver NAME         QP solver (" +
             qp::solver_names() +
             ")\n"
             "  --tol T               QP relative tolerance\n"
             "  --max-iter N          QP iteration limit\n"
             "  --coulomb-tol T       tolerance of the Coulomb fixed point "
             "(default: --tol if that\n"
             "                        is given and the .prm leaves "
             "Coulomb/Tolerance at its default)\n"
             "  --coulomb-max-iter N  limit of Coulomb iterations\n"
             "  --json FILE           write a JSON summary\n"
             "  --write FILE.hdf5     write the local problem with the "
             "solution found\n"
             "  --info                print the problem's sizes and stop\n"
             "Exit code: 0 converged, 2 not converged, 1 bad input.\n";
    }


    int
    FclibSolveDriver::run(const std::vector<std::string> &args,
                          std::ostream                   &out,
                          std::ostream                   &err) const
    {
      Options options;
      try
      {
        options = parse_options(args);
      }
      catch (const UsageError &e)
      {
        err << "fclibsolve: " << e.what() << "\n" << usage();
        return 1;
      }
      if (options.help)
      {
        out << usage();
        return 0;
      }

      try
      {
        const Settings settings = read_settings(options);
        nlohmann::json summary;
        LocalProblem   problem = naming_file(
          options.file,
          "",
          [&]() {
            return read_problem(options.file, settings.storage, out, summary);
          });
        if (options.info_only)
        {
          print_info(problem, out, summary);
          if (!options.json_file.empty())
            std::ofstream(options.json_file) << summary.dump(2) << "\n";
          return 0;
        }

        dealii::Vector<double> r(problem.size());
        bool                   converged = false;
        if (settings.loop.model == Model::newton)
        {
          const auto result =
            naming_file(options.file,
                        " (solving its problem)",
                        [&]()
                        {
                          const NewtonSolver newton(problem,
                                                    settings.loop.newton);
                          return newton.solve(r);
                        });
          print_newton_result(result, settings, out);
          compare_with_stored_solution(options.file, problem, r, out, summary);
          add_newton_result(result, settings, summary);
          converged = result.converged;
        }
        else
        {
          const auto result =
            naming_file(options.file,
                        " (solving its problem)",
                        [&]()
                        {
                          const LocalSolver local_solver(problem,
                                                         settings.qp,
                                                         settings.coulomb,
                                                         settings.loop);
                          return local_solver.solve(r);
                        });
          print_result(result, settings, out);
          compare_with_stored_solution(options.file, problem, r, out, summary);
          add_result(result, settings, summary);
          converged = result.converged;
        }
        if (!options.json_file.empty())
          write_summary(options.json_file, summary);
        if (!options.write_file.empty())
          write_local(options.write_file,
                      problem,
                      r,
                      std::string("solved by dualcontact fclibsolve, model ") +
                        model_names.name(settings.loop.model) +
                        (settings.loop.model == Model::newton ?
                           std::string() :
                           ", solver " + settings.qp.solver));
        return converged ? 0 : 2;
      }
      catch (const dealii::ExceptionBase &e)
      {
        err << "fclibsolve: " << exception_message(e) << "\n";
        return 1;
      }
      catch (const std::exception &e)
      {
        err << "fclibsolve: " << e.what() << "\n";
        return 1;
      }
    }
  } // namespace tools
} // namespace dualcontact
