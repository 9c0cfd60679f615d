#include <deal.II/base/exceptions.h>
#include <deal.II/lac/vector.h>

#include <primal/primal_parameters.h>
#include <qp/cgc.h>

namespace dualcontact
{
  namespace primal
  {
    void
    PrimalParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry(
        "Contact solver",
        "dual",
        dealii::Patterns::Selection("dual|primal"),
        "How contact scenes are solved: dual (the dual QP by the solver of "
        "`subsection QP solver') or primal (Uzawa over the friction "
        "multipliers with CGC on the non-penetration constraints, Kestranek "
        "& Nedoma 1996; `subsection Primal solver').");
      prm.enter_subsection("Primal solver");
      prm.declare_entry(
        "Preconditioner",
        "none",
        dealii::Patterns::Selection("none|diagonal|ssor|ic|icd|cholesky"),
        "Preconditioner of the CG iterations inside CGC (report, section "
        "10): none, diagonal, ssor (relaxation `SSOR omega'), ic (incomplete "
        "Cholesky on the pattern of K), icd (incomplete Cholesky with the "
        "dropped fill added to the diagonal), cholesky (complete, CHOLMOD).");
      prm.declare_entry("Version",
                        "pcg2",
                        dealii::Patterns::Selection("pcg1|pcg2"),
                        "pcg1: CG on the transformed problem y = E'x (report, "
                        "section 8); pcg2: projections around the factors "
                        "(section 9).");
      prm.declare_entry("SSOR omega",
                        "1.0",
                        dealii::Patterns::Double(0., 2.),
                        "Relaxation parameter of SSOR, in (0, 2) [-].");
      prm.declare_entry("CGC tolerance",
                        "1e-11",
                        dealii::Patterns::Double(0.),
                        "CGC stops when its projected-gradient criterion is "
                        "at most this times ||b|| [-]. The bodies' force "
                        "balance is as good as this relative to the whole "
                        "scene's loads: 1e-10 left the bridge pier's "
                        "lightest body out of balance by 1.1e-8 of its own "
                        "forces, 1e-11 by 8e-11 (9 % more CG steps).");
      prm.declare_entry("CGC maximum iterations",
                        "100000",
                        dealii::Patterns::Integer(1),
                        "Limit on the CG steps of one CGC solve.");
      prm.declare_entry("CGC loose tolerance",
                        "1e-2",
                        dealii::Patterns::Double(0.),
                        "Report, remark 7.3: during the first `CGC loose "
                        "iterations' outer iterations a facet problem counts "
                        "as solved at this times ||b|| [-].");
      prm.declare_entry("CGC loose iterations",
                        "10",
                        dealii::Patterns::Integer(0),
                        "Number of outer CGC iterations with the loose "
                        "tolerance.");
      prm.declare_entry(
        "CGC release",
        "automatic",
        dealii::Patterns::Selection(
          qp::CGC<dealii::Vector<double>>::release_names.choices()),
        "Constraints leaving the facet when the facet problem "
        "is solved: the most negative multiplier (one), all "
        "negative ones (report, lemma 7.2; safe for "
        "orthogonal rows), or all negative if the rows are "
        "orthogonal, else one (automatic).");
      prm.declare_entry(
        "CGC stopping test",
        "relative",
        dealii::Patterns::Selection(
          qp::CGC<dealii::Vector<double>>::stopping_test_names.choices()),
        "How CGC reads `CGC tolerance' (epsilon) and `CGC loose "
        "tolerance': relative (the criterion ||g^P|| at most epsilon "
        "||b||; a facet problem is solved at (loose) epsilon ||b||; a "
        "multiplier below zero is released) or report (the tests of the "
        "report, section 7 and remark 7.2, absolute in N and m: CG returns "
        "when ||(I - P_J) g||^2 < epsilon or ||x^{k+1} - x^k|| / max(1, "
        "||x^k||) < epsilon; a facet problem is solved when pg^{IT+1} / "
        "max(1, pg^{IT}) < epsilon (pg the projected gradient at the start "
        "of an outer iteration) or CG has just stopped on it; a multiplier "
        "u_i is negative when u_i / max(1, max u) < -epsilon).");
      prm.declare_entry("Uzawa step factor",
                        "1.0",
                        dealii::Patterns::Double(0.),
                        "Uzawa step rho = factor / ||G K^{-1} G'|| (G the "
                        "friction matrix psi B_T); converges for factors in "
                        "(0, 2) [-].");
      prm.declare_entry("Uzawa step",
                        "0",
                        dealii::Patterns::Double(0.),
                        "Absolute Uzawa step rho [1/J; 1/(J/m) in 2D]; 0: use "
                        "the step factor.");
      prm.declare_entry("Uzawa tolerance",
                        "1e-9",
                        dealii::Patterns::Double(0.),
                        "Uzawa stops when the largest change of a friction "
                        "multiplier mu_i (|mu_i| <= 1) is at most this [-].");
      prm.declare_entry(
        "Uzawa stopping test",
        "max change",
        dealii::Patterns::Selection("max change|relative"),
        "How `Uzawa tolerance' is applied: max change (the largest change "
        "|mu_i^{k+1} - mu_i^k| of a friction multiplier) or relative (the "
        "report's form, remark 7.2: ||mu^{k+1} - mu^k|| / max(1, ||mu^k||), "
        "Euclidean norms over all multipliers) [-].");
      prm.declare_entry(
        "Friction multipliers",
        "per node",
        dealii::Patterns::Selection("per node|per edge"),
        "Where the friction multipliers mu (|mu| <= 1) live: per node (one "
        "per contact node and tangent, the nodal slip bound g w_i) or per "
        "edge (the report's (4.4): one per slave face, piecewise constant, "
        "acting on the integral of the slip over the face; Tresca friction "
        "only).");
      prm.declare_entry("Uzawa maximum iterations",
                        "20000",
                        dealii::Patterns::Integer(1),
                        "Limit on the Uzawa iterations of one Tresca "
                        "problem.");
      prm.leave_subsection();
    }


    void
    PrimalParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      contact_solver = prm.get("Contact solver");
      prm.enter_subsection("Primal solver");
      preconditioner       = prm.get("Preconditioner");
      version              = prm.get("Version");
      omega                = prm.get_double("SSOR omega");
      cgc_tolerance        = prm.get_double("CGC tolerance");
      cgc_max_iterations   = prm.get_integer("CGC maximum iterations");
      cgc_loose_tolerance  = prm.get_double("CGC loose tolerance");
      cgc_loose_iterations = prm.get_integer("CGC loose iterations");
      cgc_release          = prm.get("CGC release");
      cgc_stopping_test    = prm.get("CGC stopping test");
      uzawa_step_factor    = prm.get_double("Uzawa step factor");
      uzawa_step           = prm.get_double("Uzawa step");
      uzawa_tolerance      = prm.get_double("Uzawa tolerance");
      uzawa_max_iterations = prm.get_integer("Uzawa maximum iterations");
      uzawa_stopping_test  = prm.get("Uzawa stopping test");
      friction_multipliers = prm.get("Friction multipliers");
      prm.leave_subsection();
      const std::string where = "' in `subsection Primal solver').";
      AssertThrow(omega > 0. && omega < 2.,
                  dealii::ExcMessage("SSOR omega must lie in (0, 2), got " +
                                     std::to_string(omega) +
                                     " (`set SSOR omega" + where));
      AssertThrow(cgc_tolerance > 0.,
                  dealii::ExcMessage("CGC tolerance must be positive (`set "
                                     "CGC tolerance" +
                                     where));
      AssertThrow(cgc_loose_tolerance > 0.,
                  dealii::ExcMessage("CGC loose tolerance must be positive "
                                     "(`set CGC loose tolerance" +
                                     where));
      AssertThrow(uzawa_tolerance > 0.,
                  dealii::ExcMessage("Uzawa tolerance must be positive (`set "
                                     "Uzawa tolerance" +
                                     where));
      AssertThrow(uzawa_stopping_test == "max change" ||
                    uzawa_stopping_test == "relative",
                  dealii::ExcMessage("Uzawa stopping test must be `max "
                                     "change' or `relative', got `" +
                                     uzawa_stopping_test +
                                     "' (`set Uzawa stopping test" + where));
      AssertThrow(friction_multipliers == "per node" ||
                    friction_multipliers == "per edge",
                  dealii::ExcMessage("Friction multipliers must be `per "
                                     "node' or `per edge', got `" +
                                     friction_multipliers +
                                     "' (`set Friction multipliers" + where));
      AssertThrow(uzawa_step > 0. ||
                    (uzawa_step_factor > 0. && uzawa_step_factor < 2.),
                  dealii::ExcMessage(
                    "Uzawa step factor must lie in (0, 2) when no absolute "
                    "Uzawa step is given, got " +
                    std::to_string(uzawa_step_factor) +
                    " (`set Uzawa step factor" + where));
    }
  } // namespace primal
} // namespace dualcontact
