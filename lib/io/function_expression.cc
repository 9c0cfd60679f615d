#include <deal.II/base/exceptions.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>
#include <deal.II/lac/vector.h>

#include <io/checked_function.h>
#include <io/function_expression.h>
#include <io/parameter_file.h>

#include <map>
#include <sstream>

namespace dualcontact
{
  namespace io
  {
    std::string
    zero_expressions(const unsigned int n_components)
    {
      std::string text;
      for (unsigned int c = 0; c < n_components; ++c)
        text += (c == 0 ? "0" : "; 0");
      return text;
    }


    template <int dim>
    std::shared_ptr<dealii::Function<dim>>
    parse_function(const std::string &expressions,
                   const unsigned int n_components,
                   const std::string &parameter_location)
    {
      const std::vector<std::string> parts =
        dealii::Utilities::split_string_list(expressions, ';');
      AssertThrow(parts.size() == n_components,
                  dealii::ExcMessage(
                    "Expected " + std::to_string(n_components) +
                    " expressions separated by `;' (one per component), got " +
                    std::to_string(parts.size()) + ": `" +
                    shorten_for_message(expressions) + "' " +
                    parameter_location + "."));
      // t: the time of a load step (subsection `Load steps'); the function
      // is evaluated at the step's time through Function::set_time()
      const std::string variables = (dim == 2 ? "x,y,t" : "x,y,z,t");
      const std::map<std::string, double> constants{
        {"pi", dealii::numbers::PI}};
      auto function =
        std::make_shared<dealii::FunctionParser<dim>>(n_components);
      try
      {
        function->initialize(variables, parts, constants, true);
        // muparser compiles lazily: evaluate once to find errors now
        dealii::Vector<double> values(n_components);
        function->vector_value(dealii::Point<dim>(), values);
      }
      catch (const dealii::ExceptionBase &exception)
      {
        std::ostringstream info;
        exception.print_info(info);
        AssertThrow(
          false,
          dealii::ExcMessage(
            "Cannot parse the function `" + shorten_for_message(expressions) +
            "' " + parameter_location + " (variables: " + variables +
            "; constant: pi): " +
            shorten_for_message(dealii::Utilities::trim(info.str()), 400)));
      }
      // every value where the scene uses it is checked to be finite
      return std::make_shared<CheckedFunction<dim>>(function,
                                                    expressions,
                                                    parameter_location);
    }


    template std::shared_ptr<dealii::Function<2>>
    parse_function<2>(const std::string &,
                      const unsigned int,
                      const std::string &);
    template std::shared_ptr<dealii::Function<3>>
    parse_function<3>(const std::string &,
                      const unsigned int,
                      const std::string &);
  } // namespace io
} // namespace dualcontact
