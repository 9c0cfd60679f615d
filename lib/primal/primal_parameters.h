#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace dualcontact
{
  namespace primal
  {
    /**
     * Parameters of the primal Uzawa-CGC method, subsection `Primal solver`
     * (report, sections 5-10).  Every tolerance is relative and
     * dimensionless.
     */
    struct PrimalParameters
    {
      /** `Contact solver` (top level): dual (the QP solver of `QP solver`
       * on the dual problem) or primal (this method). */
      std::string contact_solver = "dual";

      /** none | diagonal | ssor | ic | icd | cholesky (report: SPARSE,
       * P-DIAG, P-SOR, P-ILL, P-ILLD, P-LL). */
      std::string preconditioner = "none";
      /** pcg1 (section 8: CG in y = E'x) | pcg2 (section 9). */
      std::string version = "pcg2";
      /** SSOR relaxation omega in (0, 2). */
      double omega = 1.;

      /** CGC: stop when the projected gradient criterion <= tolerance
       * ||b|| (b the load of the current Uzawa iterate). */
      double cgc_tolerance = 1e-11;
      /** CGC: limit on the CG steps of one CGC solve. */
      unsigned int cgc_max_iterations = 100000;
      /** Remark 7.3: facet problems of the first `CGC loose iterations`
       * outer iterations count as solved at `CGC loose tolerance` ||b||. */
      double       cgc_loose_tolerance  = 1e-2;
      unsigned int cgc_loose_iterations = 10;
      /** Which constraints leave the facet at a negative multiplier:
       * one | all negative | automatic (see qp::CGC). */
      std::string cgc_release = "automatic";
      /// `CGC stopping test': relative (to ||b||) or report (remark 7.2)
      std::string cgc_stopping_test = "relative";

      /** Uzawa step rho = step factor / ||G K^{-1} G'|| (the Lipschitz
       * constant of the gradient of the dual function in mu; converges for
       * factors in (0, 2)). */
      double uzawa_step_factor = 1.;
      /** Absolute Uzawa step rho [1/J, 1/(J/m) in 2D]; 0: use the factor. */
      double uzawa_step = 0.;
      /** Stop when max_i |mu_i^{k+1} - mu_i^k| <= this. */
      double uzawa_tolerance = 1e-9;
      /** How the Uzawa tolerance is applied: "max change" (max_i
       * |mu_i^{k+1} - mu_i^k| <= tolerance) or "relative" (the report's
       * form of its tests, remark 7.2: ||mu^{k+1} - mu^k|| / max(1,
       * ||mu^k||) <= tolerance, Euclidean norms over all multipliers). */
      std::string uzawa_stopping_test = "max change";
      /** Where the friction multipliers live: "per node" (one mu per
       * contact node and tangent, G = diag(g w_i) B_T) or "per edge" (the
       * report's Lambda_h, (4.4): piecewise constant on the slave faces,
       * G_e = g sum_{i in e} w_{e,i} B_T,i with w_{e,i} = int_e phi_i ds;
       * Tresca only). */
      std::string friction_multipliers = "per node";
      /** Limit on the Uzawa iterations (per Tresca problem). */
      unsigned int uzawa_max_iterations = 20000;

      /** Declares `Contact solver` at the current level and the
       * subsection `Primal solver`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);
      /** Reads and checks them (errors name the parameter). */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace primal
} // namespace dualcontact
