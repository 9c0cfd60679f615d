#include <deal.II/base/exceptions.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <driver/load_steps.h>
#include <io/parameter_file.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace dualcontact
{
  namespace driver
  {
    void
    LoadSteps::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Load steps");
      prm.declare_entry(
        "Step times",
        "",
        dealii::Patterns::Anything(),
        "The times t_1 < t_2 < ... [-] of the quasi-static load steps, "
        "separated by commas. Every load expression (`Displacement' of a "
        "Dirichlet condition, `Traction', `Body force') may use the "
        "variable t; step k solves the scene with its loads at t_k, and "
        "friction acts on the slip increment since step k - 1 (the first "
        "step's from the unloaded state). Empty: `Number of steps' steps up "
        "to `End time', or, with `Number of steps = 0', one step at t = 1 "
        "(the static problem).");
      prm.declare_entry("Number of steps",
                        "0",
                        dealii::Patterns::Integer(0),
                        "Equal steps t_k = k End time / n, k = 1 .. n, when "
                        "`Step times' is empty; 0: one step at t = 1.");
      prm.declare_entry("End time",
                        "1",
                        dealii::Patterns::Double(),
                        "The last time [-] of `Number of steps' equal "
                        "steps.");
      prm.leave_subsection();
    }


    void
    LoadSteps::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Load steps");
      const std::string list = dealii::Utilities::trim(prm.get("Step times"));
      const int         n    = prm.get_integer("Number of steps");
      const double      end  = prm.get_double("End time");
      prm.leave_subsection();

      times.clear();
      if (!list.empty())
      {
        AssertThrow(n == 0,
                    dealii::ExcMessage(
                      "Give either `Step times' or `Number of steps', not "
                      "both " +
                      io::parameter_location("Load steps", "Number of steps") +
                      "."));
        for (const std::string &text :
             dealii::Utilities::split_string_list(list, ','))
        {
          char        *end_of_number = nullptr;
          const double t = std::strtod(text.c_str(), &end_of_number);
          AssertThrow(!text.empty() && *end_of_number == '\0' &&
                        std::isfinite(t),
                      dealii::ExcMessage(
                        "The step time `" + text + "' is not a finite number " +
                        io::parameter_location("Load steps", "Step times") +
                        "."));
          times.push_back(t);
        }
      }
      else if (n > 0)
      {
        AssertThrow(std::isfinite(end) && end > 0,
                    dealii::ExcMessage(
                      "The end time of equal steps must be finite and "
                      "positive " +
                      io::parameter_location("Load steps", "End time") + "."));
        for (int k = 1; k <= n; ++k)
          times.push_back(k * end / n);
      }
      else
        times.push_back(1.);

      for (unsigned int k = 1; k < times.size(); ++k)
      {
        std::ostringstream message;
        message << "The step times must increase: step " << k + 1
                << " at t = " << times[k] << " does not follow step " << k
                << " at t = " << times[k - 1] << " "
                << io::parameter_location("Load steps", "Step times") << ".";
        AssertThrow(times[k] > times[k - 1], dealii::ExcMessage(message.str()));
      }
    }
  } // namespace driver
} // namespace dualcontact
