#include <qp/free_set_amg.h>
#include <qp/kkt_residuals.h>
#include <qp/membrane_generator.h>
#include <qp/problem_io.h>
#include <qp/smalse_m.h>
#include <qp/solver_chain.h>
#include <qp/solver_factory.h>
#include <tools/command_line.h>
#include <tools/qpsolve_driver.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/vector.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <ctime>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace dualcontact
{
  namespace tools
  {
    using namespace qp;

    namespace
    {
      using Vec = dealii::Vector<double>;

      /// command-line usage error (exit code 1)
      struct Options
      {
        std::string problem_file;
        /// the fall-back chain with measured settings, as dualcontact's
        std::string solver = "auto";
        /// --solver given (else a base parameter set's solver is used)
        bool        solver_given = false;
        double      tolerance    = -1.;
        std::string criterion;
        long        max_iterations    = -1;
        long        stagnation_window = -1;
        double      gamma             = -1.;
        long        repeat            = 1;
        std::string expansion;
        std::string preconditioner;
        long        projected_cg_trials = -1;
        double      amg_keep_fraction   = -1.;
        std::string proportioning;
        double      projected_cg_gradient_factor = -1.;
        int         amg_reuse_aggregates         = -1;
        long        amg_smoother_sweeps          = -1;
        double      amg_aggregation_threshold    = -1.;
        double      amg_prolongator_damping      = -1.;
        std::string x_out;
        std::string json_out;
      };

      Options
      parse(const std::vector<std::string> &args)
      {
        Options o;
        for (std::size_t i = 0; i < args.size(); ++i)
        {
          const std::string &a     = args[i];
          const auto         value = [&]() -> std::string
          {
            if (i + 1 >= args.size())
              throw UsageError("option " + a + " needs a value");
            return args[++i];
          };
          // the option's value as a number the option accepts, else the
          // option's own message
          const auto integer_at_least =
            [&](const long least, const std::string &message)
          {
            const long n = parse_integer(a, value());
            if (n < least)
              throw UsageError(message);
            return n;
          };
          const auto number_where =
            [&](const auto &valid, const std::string &message)
          {
            const double x = parse_number(a, value());
            if (!valid(x))
              throw UsageError(message);
            return x;
          };
          const auto positive_number = [&]()
          {
            const std::string v = value();
            const double      x = parse_number(a, v);
            if (!(x > 0.))
              throw UsageError(a + " must be > 0 (got " + v + ")");
            return x;
          };
          if (a == "--solver")
          {
            o.solver       = value();
            o.solver_given = true;
          }
          else if (a == "--tol")
            o.tolerance = positive_number();
          else if (a == "--criterion")
            o.criterion = value();
          else if (a == "--max-iter")
            o.max_iterations = integer_at_least(1, "--max-iter must be >= 1");
          else if (a == "--stagnation-window")
            o.stagnation_window =
              integer_at_least(0,
                               "--stagnation-window must be >= 0 (0: never)");
          else if (a == "--gamma")
            o.gamma = positive_number();
          else if (a == "--repeat")
            o.repeat = integer_at_least(1, "--repeat must be >= 1");
          else if (a == "--expansion")
          {
            o.expansion = value();
            if (o.expansion != "alpha-bar" && o.expansion != "projected-cg")
              throw UsageError("--expansion: unknown expansion '" +
                               o.expansion +
                               "' (valid: alpha-bar|projected-cg)");
          }
          else if (a == "--projected-cg-trials")
            o.projected_cg_trials =
              integer_at_least(1, "--projected-cg-trials must be >= 1");
          else if (a == "--preconditioner")
          {
            o.preconditioner = value();
            if (o.preconditioner != "none" && o.preconditioner != "jacobi" &&
                o.preconditioner != "amg")
              throw UsageError("--preconditioner: unknown preconditioner '" +
                               o.preconditioner + "' (valid: none|jacobi|amg)");
          }
          else if (a == "--projected-cg-gradient-factor")
            o.projected_cg_gradient_factor = number_where(
              [](const double x) { return x == 0. || x >= 1.; },
              "--projected-cg-gradient-factor must be 0 (off) or >= 1");
          else if (a == "--proportioning")
          {
            o.proportioning = value();
            if (o.proportioning != "chopped-gradient" &&
                o.proportioning != "preconditioned")
              throw UsageError("--proportioning: unknown step '" +
                               o.proportioning +
                               "' (valid: chopped-gradient|preconditioned)");
          }
          else if (a == "--amg-keep-fraction")
            o.amg_keep_fraction =
              number_where([](const double x) { return x >= 0. && x <= 1.; },
                           "--amg-keep-fraction must be in [0, 1]");
          else if (a == "--amg-reuse-aggregates")
          {
            const std::string v = value();
            if (v != "0" && v != "1")
              throw UsageError("--amg-reuse-aggregates: '" + v +
                               "' is not 0 or 1");
            o.amg_reuse_aggregates = v == "1";
          }
          else if (a == "--amg-smoother-sweeps")
            o.amg_smoother_sweeps =
              integer_at_least(1, "--amg-smoother-sweeps must be at least 1");
          else if (a == "--amg-aggregation-threshold")
            o.amg_aggregation_threshold =
              number_where([](const double x) { return x >= 0. && x < 1.; },
                           "--amg-aggregation-threshold must be in [0, 1)");
          else if (a == "--amg-prolongator-damping")
            o.amg_prolongator_damping =
              number_where([](const double x) { return x >= 0. && x < 2.; },
                           "--amg-prolongator-damping must be in [0, 2)");
          else if (a == "--x-out")
            o.x_out = value();
          else if (a == "--json-out")
            o.json_out = value();
          else if (a == "-h" || a == "--help")
            throw UsageError("");
          else if (!a.empty() && a[0] == '-')
            throw UsageError("unknown option '" + a + "'");
          else if (o.problem_file.empty())
            o.problem_file = a;
          else
            throw UsageError("more than one problem file ('" + o.problem_file +
                             "', '" + a + "')");
        }
        if (o.problem_file.empty())
          throw UsageError("no PROBLEM.json given");
        const std::string names = solver_names();
        if (("|" + names + "|").find("|" + o.solver + "|") == std::string::npos)
          throw UsageError("--solver: unknown solver '" + o.solver +
                           "' (valid: " + names + ")");
        return o;
      }
    } // namespace


    std::string
    QPSolveDriver::usage()
    {
      return "usage: qpsolve PROBLEM.json --solver " + solver_names() +
             " [--tol T] [--criterion "
             "projected|reduced|reduced-projected] [--max-iter N] "
             "[--stagnation-window N] [--gamma G] "
             "[--expansion alpha-bar|projected-cg] "
             "[--projected-cg-trials N] [--preconditioner none|jacobi|amg] "
             "[--projected-cg-gradient-factor R] "
             "[--proportioning chopped-gradient|preconditioned] "
             "[--amg-reuse-aggregates 0|1] [--amg-keep-fraction F] "
             "[--amg-smoother-sweeps N] [--amg-aggregation-threshold T] "
             "[--amg-prolongator-damping W] [--repeat N] "
             "[--x-out FILE] [--json-out FILE] [--prm FILE.prm] "
             "[--set \"QP solver/Entry=value\"]...\n"
             "--prm, --set: the QP solver's parameters by the names of "
             "dualcontact's .prm (subsection `QP solver', see `dualcontact "
             "--print-parameters'; default solver auto; a solver's own "
             "parameters in its subsection, e.g. `QP solver/SPG-QP/m=5'); "
             "the options above override them.\n"
             "--preconditioner: MPRGP with preconditioning in face (jacobi: "
             "diag(A) on the free set; amg: Trilinos ML on A with the active "
             "rows and columns replaced by identity rows, rebuilt whenever "
             "the active set changes: with --amg-reuse-aggregates 1, the "
             "default, ML aggregates A once and recomputes its hierarchy in "
             "place for each active set; 0: a full setup each time; "
             "--amg-keep-fraction F (default 0) keeps the hierarchy while "
             "at most F * n unknowns changed state; "
             "--amg-smoother-sweeps N (default 2) Chebyshev sweeps per "
             "level, --amg-aggregation-threshold T (default 0.02) ML's "
             "strength-of-connection threshold, --amg-prolongator-damping W "
             "(default 4/3) ML's damping of the smoothed prolongator, 0: the "
             "tentative one).\n"
             "--solver auto (the default): the fall-back chain; on bound and "
             "box "
             "constraints it runs MPRGP with the settings measured best "
             "(Gamma 2, projected-CG expansion with 8 trials and gradient "
             "factor 1.25, AMG in face, preconditioned release) unless one "
             "of --gamma, --expansion, --projected-cg-trials, "
             "--projected-cg-gradient-factor, --proportioning is given "
             "(then it uses those; `QP solver/Auto/Settings=given' keeps "
             "the thesis' table 14).\n"
             "--projected-cg-gradient-factor R (>= 1; 0 = off): keep the "
             "least-cost projected-CG trial among those whose ||g^P|| is "
             "within R of the least.\n"
             "--proportioning preconditioned: MPRGP's proportioning step "
             "as a projected PCG step on the free set plus the released "
             "unknowns (needs --preconditioner).\n"
             "--repeat N solves N times from the same start and reports the "
             "least wall time (timing on a busy machine).\n"
             "Exit code 0: converged, 2: not converged, 1: bad input.";
    }


    void
    QPSolveDriver::set_base_parameters(const SolverParameters &parameters)
    {
      base_parameters = parameters;
    }


    int
    QPSolveDriver::make_membrane(const std::vector<std::string> &arguments,
                                 std::ostream                   &out,
                                 std::ostream                   &err) const
    {
      try
      {
        MembraneGenerator::Parameters prm;
        std::string                   directory;
        bool                          scale_given = false;
        for (std::size_t i = 1; i < arguments.size(); ++i)
        {
          const std::string &a = arguments[i];
          if (i + 1 >= arguments.size())
            throw UsageError(a + " needs a value");
          const std::string v = arguments[++i];
          if (a == "--dir")
            directory = v;
          else if (a == "--variant")
            prm.variant = MembraneGenerator::variant_names.value(v);
          else if (a == "--h")
          {
            // n = h^2 unknowns (and a dense-free CSR of ~5 n entries):
            // 10^4 keeps it far below any memory limit
            const double h = parse_number(a, v);
            if (!(h >= 1 && h <= 10000 && h == std::floor(h)))
              throw UsageError("--h must be an integer in [1, 10000] (got " +
                               v + ")");
            prm.h = static_cast<unsigned int>(h);
          }
          else if (a == "--p")
          {
            prm.p = parse_number(a, v);
            // p = 0 and p = 1 are the thesis' end points of the sweep
            // (the obstacle entirely low / high; scripts/bench_membrane)
            if (!(prm.p >= 0. && prm.p <= 1.))
              throw UsageError("--p must lie in [0, 1] (got " + v + ")");
          }
          else if (a == "--load-scale")
          {
            prm.load_scale = parse_number(a, v);
            scale_given    = true;
          }
          else
            throw UsageError("unknown option '" + a + "'");
        }
        if (directory.empty())
          throw UsageError("--make-membrane needs --dir DIR");
        if (!scale_given && prm.variant == MembraneGenerator::Variant::permon)
          prm.load_scale = 1.;
        const MembraneGenerator generator(prm);
        const auto              problem = generator.generate();
        const std::string file = write_problem(*problem, directory, "membrane");
        const auto        eig  = generator.exact_extreme_eigenvalues();
        nlohmann::json    j;
        j["problem"]    = file;
        j["n"]          = problem->size();
        j["norm_b"]     = problem->rhs.l2_norm();
        j["lambda_min"] = eig.first;
        j["lambda_max"] = eig.second;
        j["kappa"]      = eig.first > 0. ? eig.second / eig.first : 0.;
        out << j.dump(2) << std::endl;
        return 0;
      }
      catch (const std::exception &e)
      {
        err << "qpsolve: " << plain_message(e) << std::endl;
        return 1;
      }
    }


    namespace
    {
      /// The QP of a problem file as the solvers take it; the lambdas
      /// refer to the ProblemData, which must outlive it.
      struct BuiltProblem
      {
        Problem<Vec>                              problem;
        std::shared_ptr<SeparableSet<Vec>>        set;
        std::shared_ptr<EqualityConstraints<Vec>> equality;
        std::unique_ptr<FreeSetAMG>               amg;
      };


      /// What the runs of one solve give the report.
      struct SolveResult
      {
        Vec              x;
        SolverStatistics stats;
        double           equality_residual = -1.;
        double           least_time = std::numeric_limits<double>::infinity();
        // processor time of this process (std::clock): on a machine shared
        // with other jobs it excludes the time the solve waited for a core
        double least_cpu_time = std::numeric_limits<double>::infinity();
        // FreeSetAMG's counters before the last run
        unsigned int amg_full_setups = 0, amg_recomputes = 0, amg_kept = 0;
        // the preconditioner the (chosen) solver ran with
        std::string chosen_preconditioner;
      };


      /// The solver's parameters: the .prm ones (--prm, --set) with the
      /// command-line options over them.
      SolverParameters
      solver_parameters(const Options                         &options,
                        const std::optional<SolverParameters> &base)
      {
        SolverParameters prm;
        if (base)
          prm = *base;
        prm.solver = options.solver;
        if (options.tolerance > 0.)
          prm.tolerance = options.tolerance;
        if (!options.criterion.empty())
          prm.stopping_criterion =
            stopping_criterion_names.value(options.criterion);
        if (options.max_iterations > 0)
          prm.max_iterations = options.max_iterations;
        if (options.stagnation_window >= 0)
          prm.stagnation_window = options.stagnation_window;
        if (options.gamma > 0.)
          prm.gamma = options.gamma;
        if (!options.expansion.empty())
          prm.expansion = options.expansion;
        if (options.projected_cg_trials > 0)
          prm.projected_cg_trials = options.projected_cg_trials;
        if (!options.preconditioner.empty())
          prm.preconditioner = options.preconditioner;
        if (options.projected_cg_gradient_factor >= 0.)
          prm.projected_cg_gradient_factor =
            options.projected_cg_gradient_factor;
        if (!options.proportioning.empty())
          prm.proportioning_step = options.proportioning;
        if (prm.preconditioner != "none")
          AssertThrow(options.solver == "mprgp" || options.solver == "auto",
                      dealii::ExcMessage(
                        "--preconditioner " + prm.preconditioner +
                        ": only --solver mprgp (or auto, whose MPRGP) "
                        "preconditions in face"));
        prm.check();
        return prm;
      }


      /// The separable set of the file's constraint blocks.
      std::shared_ptr<SeparableSet<Vec>>
      make_set(const ProblemData &d)
      {
        auto set = std::make_shared<SeparableSet<Vec>>();
        for (const auto &block : d.constraints)
          for (unsigned int k = 0; k < block.count; ++k)
          {
            if (block.type == "bound")
              set->add_bound(block.first + k, block.lower[k]);
            else if (block.type == "box")
              set->add_box(block.first + k, block.lower[k], block.upper[k]);
            else if (block.type == "disc")
              set->add_disc(block.first + 2 * k, block.radius[k]);
            else if (block.type == "ellipse")
              set->add_ellipse(block.first + 2 * k,
                               block.axes[2 * k],
                               block.axes[2 * k + 1],
                               block.rotation.empty() ? 0. : block.rotation[k]);
            else if (block.type == "cone")
              set->add_cone(block.first + 3 * k, block.mu[k]);
          }
        set->finalize(d.rhs);
        return set;
      }


      /// Hessian, diagonal, the AMG in face where asked for (or where
      /// `auto` with measured settings runs MPRGP with it: bounds and
      /// boxes, no equalities; SolverChain::attempt_parameters), the set
      /// and the equality constraints.
      void
      build_problem(const ProblemData      &d,
                    const Options          &options,
                    const SolverParameters &prm,
                    BuiltProblem           &built)
      {
        Problem<Vec> &problem = built.problem;
        problem.hessian       = [&d](Vec &dst, const Vec &src)
        { d.hessian.vmult(dst, src); };
        problem.b     = d.rhs;
        auto diagonal = std::make_shared<Vec>(d.size());
        for (unsigned int i = 0; i < d.size(); ++i)
          (*diagonal)[i] = d.hessian.diag_element(i);
        problem.diagonal        = diagonal;
        problem.hessian_storage = HessianStorage::sparse_matrix;
        bool only_bounds        = true;
        for (const auto &block : d.constraints)
          only_bounds =
            only_bounds && (block.type == "bound" || block.type == "box");
        const bool auto_amg = prm.solver == "auto" &&
                              prm.auto_chain.settings == "measured" &&
                              only_bounds && !d.has_equality();
        if (prm.preconditioner == "amg" || auto_amg)
        {
          FreeSetAMG::Parameters amg_parameters;
          if (options.amg_keep_fraction >= 0.)
            amg_parameters.keep_fraction = options.amg_keep_fraction;
          if (options.amg_reuse_aggregates >= 0)
            amg_parameters.reuse_aggregates = options.amg_reuse_aggregates;
          if (options.amg_smoother_sweeps > 0)
            amg_parameters.smoother_sweeps = options.amg_smoother_sweeps;
          if (options.amg_aggregation_threshold >= 0.)
            amg_parameters.aggregation_threshold =
              options.amg_aggregation_threshold;
          if (options.amg_prolongator_damping >= 0.)
            amg_parameters.prolongator_damping =
              options.amg_prolongator_damping;
          built.amg = std::make_unique<FreeSetAMG>(d.hessian, amg_parameters);
          problem.free_set_preconditioner = built.amg->factory();
        }
        built.set           = make_set(d);
        problem.constraints = built.set;
        if (d.has_equality())
        {
          auto equality   = std::make_shared<EqualityConstraints<Vec>>();
          equality->vmult = [&d](Vec &dst, const Vec &src)
          { d.equality_matrix.vmult(dst, src); };
          equality->Tvmult = [&d](Vec &dst, const Vec &src)
          { d.equality_matrix.Tvmult(dst, src); };
          equality->c             = d.equality_rhs;
          equality->n_constraints = d.equality_rhs.size();
          problem.equality        = equality;
          built.equality          = equality;
          AssertThrow(prm.preconditioner == "none",
                      dealii::ExcMessage(
                        options.problem_file +
                        ": --preconditioner is not available with "
                        "equality constraints (SMALSE-M)"));
        }
      }


      /// --repeat N solves from the same start; the least wall and
      /// processor times.
      SolveResult
      solve_repeatedly(const ProblemData      &d,
                       const Options          &options,
                       const SolverParameters &prm,
                       BuiltProblem           &built)
      {
        SolveResult result;
        result.x.reinit(d.size());
        result.chosen_preconditioner = prm.preconditioner;
        Vec                &x        = result.x;
        const Problem<Vec> &problem  = built.problem;
        for (long run = 0; run < options.repeat; ++run)
        {
          const std::clock_t cpu_start = std::clock();
          if (built.amg)
          {
            // every run from scratch: no aggregates of the previous run
            built.amg->reset();
            result.amg_full_setups = built.amg->n_full_setups();
            result.amg_recomputes  = built.amg->n_recomputes();
            result.amg_kept        = built.amg->n_kept();
          }
          x = 0.;
          if (d.x0.size() > 0)
            x = d.x0;
          // the fall-back chain, SMALSE-M around the solver with equality
          // constraints, or the solver itself
          auto solver  = make_solver<Vec>(prm, SMALSEMParameters(), problem);
          result.stats = solver->solve(problem, x);
          // the settings the chain chose (its chosen attempt's)
          if (const auto *chain =
                dynamic_cast<const SolverChain<Vec> *>(solver.get()))
            result.chosen_preconditioner =
              chain->chosen_parameters().preconditioner;
          if (problem.equality)
            result.equality_residual = solver->equality_residual();
          result.least_time =
            std::min(result.least_time, result.stats.wall_time);
          result.least_cpu_time =
            std::min(result.least_cpu_time,
                     double(std::clock() - cpu_start) / CLOCKS_PER_SEC);
        }
        return result;
      }


      /// One sparse mat-vec, for the cost per Hessian product: the least
      /// average over 10 batches (robust to other processes' load).
      void
      add_matvec_time(const ProblemData &d, const Vec &x, nlohmann::json &j)
      {
        Vec    y(x.size());
        double least     = std::numeric_limits<double>::infinity();
        double least_cpu = std::numeric_limits<double>::infinity();
        for (unsigned int batch = 0; batch < 10; ++batch)
        {
          dealii::Timer      timer;
          const std::clock_t cpu_start  = std::clock();
          unsigned int       n_products = 0;
          do
          {
            d.hessian.vmult(y, x);
            ++n_products;
          } while (timer.wall_time() < 0.02 && n_products < 100);
          least     = std::min(least, timer.wall_time() / n_products);
          least_cpu = std::min(least_cpu,
                               double(std::clock() - cpu_start) /
                                 CLOCKS_PER_SEC / n_products);
        }
        j["matvec_time"]     = json_number(least);
        j["matvec_cpu_time"] = json_number(least_cpu);
        // deal.II's SparseMatrix::vmult (here and in the solver's
        // products) runs on this many threads; the solver's vector passes
        // on one.  DEAL_II_NUM_THREADS=1 compares like with like.
        j["threads"] = dealii::MultithreadInfo::n_threads();
      }


      /// The problem's size and blocks.
      void
      add_problem_summary(const ProblemData &d,
                          const Options     &options,
                          nlohmann::json    &j)
      {
        j["problem"]          = options.problem_file;
        j["n"]                = d.size();
        j["nonzeros"]         = d.hessian.n_nonzero_elements();
        nlohmann::json blocks = nlohmann::json::object();
        for (const char *type : {"bound", "box", "disc", "ellipse", "cone"})
          blocks[type] = 0;
        std::size_t n_constrained = 0;
        for (const auto &block : d.constraints)
        {
          blocks[block.type] =
            blocks[block.type].get<unsigned int>() + block.count;
          n_constrained += block.n_unknowns();
        }
        blocks["free_unknowns"] = d.size() - n_constrained;
        j["blocks"]             = blocks;
        if (d.has_equality())
          j["equality_constraints"] = d.equality_rhs.size();
      }


      /// The JSON report (stdout and --json-out).
      nlohmann::json
      report(const ProblemData  &d,
             const Options      &options,
             const double        read_time,
             const SolveResult  &result,
             const BuiltProblem &built)
      {
        const SolverStatistics &stats = result.stats;
        nlohmann::json          j;
        add_problem_summary(d, options, j);
        j["read_time"] = json_number(read_time);
        {
          std::ostringstream s;
          stats.write_json(s, false);
          j["statistics"] = nlohmann::json::parse(s.str());
        }
        // the headline figures also at the top level
        j["solver"]           = stats.solver;
        j["reason"]           = to_string(stats.reason);
        j["converged"]        = stats.converged();
        j["iterations"]       = stats.iterations;
        j["hessian_products"] = stats.n_hessian_products;
        j["time"]             = json_number(result.least_time);
        j["runs"]             = options.repeat;
        j["cpu_time"]         = json_number(result.least_cpu_time);
        j["final_criterion"]  = json_number(stats.final_criterion);
        j["preconditioner"]   = result.chosen_preconditioner;
        if (!stats.settings.empty())
          j["settings"] = stats.settings;
        j["preconditioner_setups"] = stats.n_preconditioner_setups;
        j["preconditioner_setup_time"] =
          json_number(stats.preconditioner_setup_time);
        j["preconditioner_applications"] = stats.n_preconditioner_applications;
        j["preconditioner_apply_time"] =
          json_number(stats.preconditioner_apply_time);
        if (built.amg)
        {
          // of the last run: full ML setups and in-place recomputes
          j["amg_full_setups"] =
            built.amg->n_full_setups() - result.amg_full_setups;
          j["amg_recomputes"] =
            built.amg->n_recomputes() - result.amg_recomputes;
          j["amg_kept"] = built.amg->n_kept() - result.amg_kept;
        }
        j["kkt"] = j["statistics"]["kkt"];
        if (result.equality_residual >= 0.)
        {
          j["equality_residual"] = json_number(result.equality_residual);
          j["outer_iterations"]  = stats.n_outer;
        }
        {
          const auto     active = built.set->n_active_blocks(result.x);
          nlohmann::json a;
          for (unsigned int t = 0; t < n_block_types; ++t)
            a[block_type_names.name(static_cast<BlockType>(t))] = active[t];
          j["active_blocks"] = a;
        }
        add_matvec_time(d, result.x, j);
        return j;
      }


      /// --x-out and --json-out.
      void
      write_outputs(const Options     &options,
                    const std::string &text,
                    const Vec         &x)
      {
        if (!options.x_out.empty())
          write_vector_file(options.x_out, x);
        if (!options.json_out.empty())
        {
          std::ofstream file(options.json_out);
          AssertThrow(file,
                      dealii::ExcMessage("cannot write --json-out file '" +
                                         options.json_out + "'"));
          file << text << '\n';
        }
      }
    } // namespace


    int
    QPSolveDriver::run(const std::vector<std::string> &arguments,
                       std::ostream                   &out,
                       std::ostream                   &err) const
    {
      if (!arguments.empty() && arguments[0] == "--make-membrane")
        return make_membrane(arguments, out, err);
      Options options;
      try
      {
        options = parse(arguments);
        if (base_parameters && !options.solver_given)
          options.solver = base_parameters->solver;
      }
      catch (const UsageError &e)
      {
        if (std::string(e.what()).size() > 0)
          err << "qpsolve: " << e.what() << '\n';
        err << usage() << std::endl;
        return 1;
      }

      // every failure below is bad input (exit 1) or a solver that broke
      // down (exit 1); not converged is exit 2
      const auto fail = [&err](const std::exception &e)
      {
        err << "qpsolve: " << plain_message(e) << std::endl;
        return 1;
      };
      dealii::Timer                read_timer;
      std::unique_ptr<ProblemData> data;
      SolverParameters             prm;
      BuiltProblem                 built;
      try
      {
        data = read_problem(options.problem_file);
        prm  = solver_parameters(options, base_parameters);
        build_problem(*data, options, prm, built);
      }
      catch (const std::exception &e)
      {
        return fail(e);
      }
      const double read_time = read_timer.wall_time();

      SolveResult result;
      try
      {
        result = solve_repeatedly(*data, options, prm, built);
      }
      catch (const std::exception &e)
      {
        return fail(e);
      }

      const std::string text =
        report(*data, options, read_time, result, built).dump(2);
      out << text << std::endl;
      try
      {
        write_outputs(options, text, result.x);
      }
      catch (const std::exception &e)
      {
        return fail(e);
      }
      const SolverStatistics &stats = result.stats;
      if (!stats.converged())
        err << "qpsolve: not converged: " << to_string(stats.reason)
            << (stats.message.empty() ? "" : " (" + stats.message + ")")
            << std::endl;
      return stats.converged() ? 0 : 2;
    }

  } // namespace tools
} // namespace dualcontact
