#pragma once

#include <deal.II/base/parameter_handler.h>

#include <fem/stiffness_solver.h>

#include <memory>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * The solver of one TFETI subdomain from `subsection Stiffness
     * solver': a factor that stays on the process owning the subdomain,
     * whatever the number of processes.  `Solver = umfpack' gives UMFPACK;
     * every other choice (cholmod, and the distributed mumps and amg,
     * which serve the undecomposed path under MPI) gives CHOLMOD with the
     * `Ordering' given there (`automatic' is nested dissection here: its
     * factors are the smallest, and a subdomain's factor serves hundreds
     * of solves): a subdomain is small, floating and factorized once,
     * which is what a serial sparse Cholesky does best.
     */
    std::unique_ptr<fem::StiffnessSolver>
    make_subdomain_solver(dealii::ParameterHandler &prm);
  } // namespace decomposition
} // namespace dualcontact
