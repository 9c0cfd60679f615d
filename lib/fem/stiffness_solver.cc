#include <deal.II/base/mpi.h>

#include <fem/cholmod_solver.h>
#include <fem/stiffness_solver.h>
#include <fem/trilinos_solver.h>
#include <fem/umfpack_solver.h>
#include <util/blas_kernels.h>

#include <string>

namespace dualcontact
{
  namespace fem
  {
    const StiffnessSolver::Statistics &
    StiffnessSolver::statistics() const
    {
      return statistics_;
    }


    void
    StiffnessSolver::set_monitor(
      std::function<void(const std::string &)> monitor)
    {
      monitor_ = std::move(monitor);
    }


    bool
    StiffnessSolver::offers_schur_factor() const
    {
      return false;
    }


    bool
    StiffnessSolver::is_distributed() const
    {
      return false;
    }


    void
    StiffnessSolver::initialize_with_schur_factor(
      const dealii::SparseMatrix<double> &,
      const std::vector<dealii::types::global_dof_index> &,
      SchurFactor &)
    {
      AssertThrow(false,
                  dealii::ExcMessage("The stiffness solver `" + name() +
                                     "' cannot factor a Schur complement; "
                                     "use `set Solver = cholmod' in "
                                     "`subsection Stiffness solver', or "
                                     "`set Operator = implicit' in "
                                     "`subsection Dual problem'."));
    }


    void
    StiffnessSolver::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Stiffness solver");
      prm.declare_entry(
        "Solver",
        "automatic",
        dealii::Patterns::Selection("automatic|cholmod|umfpack|mumps|amg"),
        "How K^{-1} is applied. automatic: cholmod, on any number of "
        "processes; beyond `Decomposition/Memory limit' (the factor's "
        "copies on the machine) TFETI takes over in a contact scene, mumps "
        "in a scene without contact. cholmod: supernodal sparse Cholesky "
        "(SuiteSparse CHOLMOD, long-integer interface), the fastest on one "
        "process in 2D and 3D. umfpack: sparse LU (deal.II's "
        "SparseDirectUMFPACK); fine in 2D, slow in 3D (190 s against 7 s for "
        "CHOLMOD on a 92k-dof matrix). mumps: distributed sparse LU (MUMPS "
        "through Trilinos Amesos). amg: conjugate gradients preconditioned "
        "by Trilinos ML algebraic multigrid, to `CG tolerance'. Under MPI "
        "(mpirun -np N, N > 1) cholmod and umfpack factorize the whole "
        "matrix on every process and solve there (as fast as one process, "
        "N copies of the factor), mumps and amg spread it over the "
        "processes (less memory a process, a collective solve a Hessian "
        "product: slower where one factor fits).");
      prm.declare_entry(
        "Ordering",
        "automatic",
        dealii::Patterns::Selection(CholmodSolver::ordering_names.choices()),
        "Fill-reducing ordering of CHOLMOD. automatic: CHOLMOD's default "
        "(AMD, then METIS if AMD gives much fill) for a body's factor, "
        "nested dissection for TFETI's subdomains (their factors serve "
        "hundreds of solves, and NESDIS' is the smallest: level-40 brick, "
        "128 subdomains on two processes, 88.0 -> 71.7 ms a Hessian "
        "product and 1.32 -> 1.13 GB a process against CHOLMOD's default); "
        "amd; metis; nested dissection (CHOLMOD's NESDIS).");
      prm.declare_entry("CG tolerance",
                        "1e-12",
                        dealii::Patterns::Double(0., 1.),
                        "Solver = amg: CG stops when ||K x - b|| <= this "
                        "times ||b|| [-]. The dual operator B K^{-1} B' is "
                        "applied to this accuracy, so keep it well below the "
                        "QP tolerance.");
      prm.declare_entry("CG max iterations",
                        "10000",
                        dealii::Patterns::Integer(1),
                        "Solver = amg: iteration limit of CG; reaching it "
                        "is an error.");
      prm.declare_entry("AMG aggregation threshold",
                        "1e-4",
                        dealii::Patterns::Double(0., 1.),
                        "Solver = amg: ML's aggregation threshold [-] (the "
                        "strength of a connection that lets two nodes join "
                        "one aggregate).");
      prm.declare_entry("AMG smoother sweeps",
                        "2",
                        dealii::Patterns::Integer(1),
                        "Solver = amg: Chebyshev smoother sweeps per level.");
      prm.declare_entry(
        "BLAS threads",
        "automatic",
        dealii::Patterns::Anything(),
        "Threads of OpenBLAS (the factorization's dense kernels and the "
        "dense dual operator): a number >= 1, or automatic: one per process "
        "under MPI, OPENBLAS_NUM_THREADS or OMP_NUM_THREADS where the user "
        "set them, otherwise the cores the load average leaves idle (at "
        "least one). OpenBLAS' threads spin while they wait, so on cores "
        "that other processes keep busy they slow the run down: 3D Hertz "
        "took 1.2 s with two threads on an idle 2-core machine, 1.6 s with "
        "one and 22 s with two beside two busy processes.");
      prm.leave_subsection();
    }


    std::string
    StiffnessSolver::apply_blas_threads(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Stiffness solver");
      const std::string setting = prm.get("BLAS threads");
      prm.leave_subsection();
      const unsigned int n_processes =
        dealii::Utilities::MPI::job_supports_mpi() ?
          dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) :
          1;
      util::BlasThreadChoice choice;
      if (setting == "automatic")
        choice = util::automatic_blas_threads(n_processes);
      else
      {
        std::size_t end     = 0;
        int         threads = 0;
        try
        {
          threads = std::stoi(setting, &end);
        }
        catch (const std::exception &)
        {
          end = 0;
        }
        AssertThrow(end > 0 && end == setting.size() && threads >= 1,
                    dealii::ExcMessage(
                      "`set BLAS threads = " + setting +
                      "' in `subsection Stiffness solver': must be "
                      "`automatic' or a whole number >= 1."));
        choice = {threads, "set in the input"};
      }
      util::use_blas_threads(choice);
      return std::to_string(util::blas_threads()) + " (" + choice.reason + ")";
    }


    std::string
    StiffnessSolver::resolved_name(const std::string &name)
    {
      // cholmod on any number of processes: where the undecomposed path
      // runs (its factor fits `Decomposition/Memory limit' on every
      // process of a machine), the whole factor on every process is as
      // fast as one process, where MUMPS' distributed solves made every
      // Hessian product a collective solve (3D Hertz on two processes:
      // QP 5.7 s against 0.02 s); beyond the limit TFETI takes over
      return name == "automatic" ? "cholmod" : name;
    }


    bool
    StiffnessSolver::spreads_over_processes(const std::string &solver)
    {
      return solver == "mumps" || solver == "amg";
    }


    std::unique_ptr<StiffnessSolver>
    StiffnessSolver::create(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Stiffness solver");
      const std::string solver = resolved_name(prm.get("Solver"));
      prm.leave_subsection();
      return create(prm, solver);
    }


    std::unique_ptr<StiffnessSolver>
    StiffnessSolver::create(dealii::ParameterHandler &prm,
                            const std::string        &solver)
    {
      prm.enter_subsection("Stiffness solver");
      const std::string          ordering = prm.get("Ordering");
      TrilinosSolver::Parameters trilinos;
      trilinos.method = solver == "mumps" ? TrilinosSolver::Method::mumps :
                                            TrilinosSolver::Method::amg_cg;
      trilinos.cg_tolerance      = prm.get_double("CG tolerance");
      trilinos.cg_max_iterations = prm.get_integer("CG max iterations");
      trilinos.aggregation_threshold =
        prm.get_double("AMG aggregation threshold");
      trilinos.smoother_sweeps = prm.get_integer("AMG smoother sweeps");
      prm.leave_subsection();
      if (spreads_over_processes(solver))
        return std::make_unique<TrilinosSolver>(trilinos);
      // cholmod and umfpack under MPI: every process factorizes the whole
      // matrix (it holds the whole K anyway) and solves on its own
      if (solver == "cholmod")
        return std::make_unique<CholmodSolver>(
          CholmodSolver::ordering_names.value(ordering));
      if (solver == "umfpack")
        return std::make_unique<UmfpackSolver>();
      AssertThrow(false,
                  dealii::ExcMessage("Unknown stiffness solver `" + solver +
                                     "' (`set Solver' in `subsection "
                                     "Stiffness solver')."));
      return nullptr;
    }
  } // namespace fem
} // namespace dualcontact
