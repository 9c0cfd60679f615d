#include <fem/cholmod_solver.h>
#include <fem/stiffness_solver.h>
#include <fem/umfpack_solver.h>

namespace dualcontact
{
  namespace fem
  {
    const StiffnessSolver::Statistics &
    StiffnessSolver::statistics() const
    {
      return statistics_;
    }


    bool
    StiffnessSolver::offers_schur_factor() const
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
        "cholmod",
        dealii::Patterns::Selection("cholmod|umfpack"),
        "How K^{-1} is applied. cholmod: supernodal sparse Cholesky "
        "(SuiteSparse CHOLMOD, long-integer interface), the fastest on one "
        "process in 2D and 3D. umfpack: sparse LU (deal.II's "
        "SparseDirectUMFPACK); fine in 2D, slow in 3D (190 s against 7 s for "
        "CHOLMOD on a 92k-dof matrix).");
      prm.declare_entry(
        "Ordering",
        "automatic",
        dealii::Patterns::Selection("automatic|amd|metis|nested dissection"),
        "Fill-reducing ordering of CHOLMOD. automatic: CHOLMOD's default "
        "(AMD, then METIS if AMD gives much fill); amd; metis; nested "
        "dissection (CHOLMOD's NESDIS).");
      prm.leave_subsection();
    }


    std::unique_ptr<StiffnessSolver>
    StiffnessSolver::create(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Stiffness solver");
      const std::string solver   = prm.get("Solver");
      const std::string ordering = prm.get("Ordering");
      prm.leave_subsection();
      if (solver == "cholmod")
        return std::make_unique<CholmodSolver>(
          CholmodSolver::parse_ordering(ordering));
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
