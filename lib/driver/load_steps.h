#pragma once

#include <deal.II/base/parameter_handler.h>

#include <vector>

namespace dualcontact
{
  namespace driver
  {
    /**
     * Subsection `Load steps': the times t_1 < t_2 < ... of a quasi-static
     * load history (design.md, "Load history").  Every load expression
     * (prescribed displacements, tractions, body forces) may use the
     * variable t; each step solves the scene with its loads at t_k, and
     * friction acts on the slip increment from the previous step.
     *
     * Either `Step times' (a list) or `Number of steps' with `End time'
     * (equal steps t_k = k End time / n); neither: one step at t = 1, the
     * static problem (the default, every scene without a history).
     */
    struct LoadSteps
    {
      /** The step times, increasing, finite; at least one. */
      std::vector<double> times{1.};

      /** Whether the scene has more than one step (a history). */
      bool
      is_history() const
      {
        return times.size() > 1;
      }

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      /** Reads and checks the times (errors name the parameter). */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace driver
} // namespace dualcontact
