#include <tools/command_line.h>

#include <cmath>

namespace dualcontact
{
  namespace tools
  {
    double
    parse_number(const std::string &option,
                 const std::string &value,
                 const bool         finite)
    {
      double number = 0.;
      try
      {
        std::size_t used = 0;
        number           = std::stod(value, &used);
        if (used != value.size())
          throw std::invalid_argument(value);
      }
      catch (const std::exception &)
      {
        throw UsageError(option + ": '" + value + "' is not a number");
      }
      if (std::isnan(number))
        throw UsageError(option + ": '" + value + "' is not a number");
      if (finite && !std::isfinite(number))
        throw UsageError(option + ": '" + value + "' is not a finite number");
      return number;
    }


    long
    parse_integer(const std::string &option, const std::string &value)
    {
      try
      {
        std::size_t used   = 0;
        const long  number = std::stol(value, &used);
        if (used == value.size())
          return number;
      }
      catch (const std::exception &)
      {
      }
      throw UsageError(option + ": '" + value + "' is not an integer");
    }
  } // namespace tools
} // namespace dualcontact
