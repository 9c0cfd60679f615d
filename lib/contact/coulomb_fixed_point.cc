#include <deal.II/base/exceptions.h>

#include <contact/coulomb_fixed_point.h>

#include <cmath>
#include <sstream>

namespace dualcontact
{
  namespace contact
  {
    void
    CoulombParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Coulomb");
      prm.declare_entry("Tolerance",
                        "1e-6",
                        dealii::Patterns::Double(0.),
                        "Coulomb friction is solved as a fixed point over "
                        "Tresca problems, psi_i = mu lambda_N,i; it stops when "
                        "the relative change of the slip bounds psi is below "
                        "this value [-].");
      prm.declare_entry("Maximum iterations",
                        "50",
                        dealii::Patterns::Integer(1),
                        "Limit on the Coulomb fixed-point iterations; reaching "
                        "it is reported as not converged.");
      prm.declare_entry("Divergence window",
                        "5",
                        dealii::Patterns::Integer(2),
                        "The fixed point is declared divergent when the change "
                        "of psi grew in this many consecutive iterations.");
      prm.leave_subsection();
    }


    void
    CoulombParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Coulomb");
      tolerance         = prm.get_double("Tolerance");
      max_iterations    = prm.get_integer("Maximum iterations");
      divergence_window = prm.get_integer("Divergence window");
      prm.leave_subsection();
    }


    CoulombFixedPoint::CoulombFixedPoint(const CoulombParameters &parameters)
        : parameters(parameters)
    {
    }


    double
    CoulombFixedPoint::relative_change(const double change_squared,
                                       const double norm_squared)
    {
      return norm_squared > 0. ? std::sqrt(change_squared / norm_squared) :
                                 std::sqrt(change_squared);
    }


    CoulombFixedPoint::State
    CoulombFixedPoint::record_change(const double relative_change)
    {
      Assert(current == State::iterating,
             dealii::ExcMessage("The fixed point has stopped already."));
      growing = (!recorded.empty() && relative_change > recorded.back()) ?
                  growing + 1 :
                  0;
      recorded.push_back(relative_change);
      if (!std::isfinite(relative_change))
        current = State::not_finite;
      else if (relative_change <= parameters.tolerance)
        current = State::converged;
      else if (growing >= parameters.divergence_window)
        current = State::diverged;
      else if (recorded.size() >= parameters.max_iterations)
        current = State::iteration_limit;
      return current;
    }


    const std::vector<double> &
    CoulombFixedPoint::changes() const
    {
      return recorded;
    }


    std::string
    CoulombFixedPoint::message() const
    {
      switch (current)
      {
        case State::iterating:
          return "";
        case State::converged:
          return "converged";
        case State::diverged:
          return "Coulomb fixed point diverged (the change of psi grew in " +
                 std::to_string(growing) + " consecutive iterations)";
        case State::iteration_limit:
        {
          std::ostringstream text;
          text << "Coulomb fixed point: maximum iterations ("
               << parameters.max_iterations << ") reached, relative change "
               << recorded.back();
          return text.str();
        }
        case State::not_finite:
          return "Coulomb fixed point: non-finite slip bounds";
      }
      Assert(false, dealii::ExcInternalError());
      return "";
    }
  } // namespace contact
} // namespace dualcontact
