/**
 * @file command_line.h
 * What the programs' drivers share in reading their options: the error a
 * wrong option raises (reported with the usage text and exit code 1) and
 * the conversion of an option's value to a number, with messages that name
 * the option.
 */
#ifndef dualcontact_tools_command_line_h
#define dualcontact_tools_command_line_h

#include <stdexcept>
#include <string>

namespace dualcontact
{
  namespace tools
  {
    /** A wrong command line: unknown option, missing or bad value. */
    struct UsageError : std::runtime_error
    {
      using std::runtime_error::runtime_error;
    };

    /**
     * @p value (of option @p option) as a number: all of it must be read;
     * NaN is no number, and with @p finite neither is +-inf.  Throws
     * UsageError "OPTION: 'VALUE' is not a number" (or "... not a finite
     * number").
     */
    double
    parse_number(const std::string &option,
                 const std::string &value,
                 bool               finite = true);

    /**
     * @p value as an integer (all of it read); throws UsageError "OPTION:
     * 'VALUE' is not an integer" otherwise, also beyond the range of long.
     */
    long
    parse_integer(const std::string &option, const std::string &value);
  } // namespace tools
} // namespace dualcontact

#endif
