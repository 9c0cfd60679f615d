#pragma once

// Shared by the test programs: a named check that prints its value and
// counts failures, and the exit status.  Tests print what they checked, so
// a failing ctest log says which number was wrong.

#include <iostream>
#include <string>

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

  /** Final line and exit status of a test program. */
  inline int
  finish()
  {
    std::cout << (failures == 0 ? "all checks passed" : "FAILED") << std::endl;
    return failures == 0 ? 0 : 1;
  }
} // namespace test_tools
