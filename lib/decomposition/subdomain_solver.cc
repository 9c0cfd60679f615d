#include <decomposition/subdomain_solver.h>
#include <fem/cholmod_solver.h>
#include <fem/umfpack_solver.h>

namespace dualcontact
{
  namespace decomposition
  {
    std::unique_ptr<fem::StiffnessSolver>
    make_subdomain_solver(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Stiffness solver");
      const std::string solver   = prm.get("Solver");
      const std::string ordering = prm.get("Ordering");
      prm.leave_subsection();
      if (solver == "umfpack")
        return std::make_unique<fem::UmfpackSolver>();
      // A subdomain's factor serves every Hessian product of the QP, so
      // the solves' memory traffic (the factor's size) decides, not the
      // factorization: CHOLMOD's nested dissection gives the smallest
      // factors of the orderings measured (level-40 brick in 128
      // subdomains, two processes: 71.7 ms a product against 75.3 with
      // METIS and 88.0 with CHOLMOD's default; doc/benchmarks/tfeti.md).
      const auto chosen = fem::CholmodSolver::ordering_names.value(ordering);
      return std::make_unique<fem::CholmodSolver>(
        chosen == fem::CholmodSolver::Ordering::automatic ?
          fem::CholmodSolver::Ordering::nested_dissection :
          chosen);
    }
  } // namespace decomposition
} // namespace dualcontact
