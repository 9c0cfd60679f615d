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
      return std::make_unique<fem::CholmodSolver>(
        fem::CholmodSolver::ordering_names.value(ordering));
    }
  } // namespace decomposition
} // namespace dualcontact
