#pragma once

// Shared by the test programs: a named check that prints its value and
// counts failures, and the exit status.  Tests print what they checked, so
// a failing ctest log says which number was wrong.

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/vector.h>

#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace test_tools
{
  inline int failures = 0;

  /** Print "ok"/"FAIL", the description and the measured value. */
  template <typename Value>
  void
  check(const bool ok, const std::string &what, const Value &value)
  {
    std::cout << (ok ? "  ok   " : "  FAIL ") << what << ": " << value
              << std::endl;
    if (!ok)
      ++failures;
  }

  /** Print "ok"/"FAIL" and the description (a check without a value). */
  inline void
  check(const bool ok, const std::string &what)
  {
    std::cout << (ok ? "  ok   " : "  FAIL ") << what << std::endl;
    if (!ok)
      ++failures;
  }

  /** The message of the deal.II exception @p function throws ("" if it
   *  throws none). */
  template <typename Function>
  std::string
  error_of(const Function &function)
  {
    try
    {
      function();
    }
    catch (const dealii::ExceptionBase &exception)
    {
      std::ostringstream info;
      exception.print_info(info);
      return info.str();
    }
    return "";
  }

  /** Whether @p text contains @p part; prints @p text where it does not,
   *  so that a failing check shows the message it got. */
  inline bool
  contains(const std::string &text, const std::string &part)
  {
    const bool found = text.find(part) != std::string::npos;
    if (!found)
      std::cout << "      message: " << text.substr(0, 600) << std::endl;
    return found;
  }

  /** The Euclidean distance between @p a and the expected values @p b. */
  inline double
  distance(const dealii::Vector<double> &a, const std::vector<double> &b)
  {
    double s = 0;
    for (unsigned int i = 0; i < a.size(); ++i)
      s += std::pow(a(i) - b[i], 2);
    return std::sqrt(s);
  }

  /** Final line and exit status of a test program. */
  inline int
  finish()
  {
    std::cout << (failures == 0 ? "all checks passed" : "FAILED") << std::endl;
    return failures == 0 ? 0 : 1;
  }
} // namespace test_tools
