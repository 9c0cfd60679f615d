// io::outline_parameter_file, io::check_double_entries and the byte-order
// mark: what deal.II's ParameterHandler accepts silently (a key set twice,
// a subnormal value) or does not survive (a file including itself) is an
// error that names the parameter or the chain of files; a UTF-8 byte-order
// mark is skipped; huge values are not echoed whole.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <io/parameter_file.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <test_tools.h>

namespace fs = std::filesystem;

using test_tools::check;
using test_tools::contains;
using test_tools::error_of;

namespace
{
  void
  write(const std::string &name, const std::string &text)
  {
    std::ofstream(name) << text;
  }

  void
  declare(dealii::ParameterHandler &prm)
  {
    prm.declare_entry("Dimension", "3", dealii::Patterns::Integer(2, 3));
    prm.enter_subsection("Body 1");
    prm.declare_entry("Young's modulus", "1", dealii::Patterns::Double());
    prm.declare_entry("Name", "a", dealii::Patterns::Selection("a|b"));
    prm.leave_subsection();
  }
} // namespace


int
main()
{
  using namespace dualcontact::io;
  const fs::path root = fs::absolute("parameter_file_checks_test");
  fs::remove_all(root);
  fs::create_directories(root);
  fs::current_path(root); // deal.II finds included files from here

  // the outline: subsections opened, in included files too
  write("base.prm", "subsection Body 1\n  set Name = a\nend\n");
  write("main.prm",
        "include base.prm\nsubsection Body 1 # comment\n  subsection "
        "Material 2\n  end\n  set Name = b\nend\n");
  {
    const auto outline = outline_parameter_file("main.prm");
    check(outline.subsections ==
            std::set<std::string>{"Body 1", "Body 1/Material 2"},
          "outline: the subsections of the file and its include");
  }

  // a key set twice in one file is an error naming both lines; a file may
  // override what it includes (above: `Name' in base.prm and main.prm)
  write("twice.prm",
        "subsection Body 1\n  set Name = a\nend\nsubsection Body 1\n"
        "  set Name   = b\nend\n");
  check(contains(error_of([] { outline_parameter_file("twice.prm"); }),
                 "(`set Name' in `subsection Body 1') is set twice in the "
                 "input file `twice.prm', in line 2 and in line 5"),
        "duplicate key: both lines named");
  check(error_of([] { outline_parameter_file("main.prm"); }).empty(),
        "an include may be overridden");

  // include cycles: direct and through another file; depth limit
  write("self.prm", "set Dimension = 2\ninclude self.prm\n");
  check(contains(error_of([] { outline_parameter_file("self.prm"); }),
                 "includes itself"),
        "a file including itself");
  write("ping.prm", "include pong.prm\n");
  write("pong.prm", "include ping.prm\n");
  {
    dealii::ParameterHandler prm;
    declare(prm);
    const std::string message =
      error_of([&] { parse_parameter_file(prm, "ping.prm", false); });
    check(contains(message, "ping.prm' includes `") &&
            contains(message, "pong.prm' includes `ping.prm'"),
          "a cycle through two files: parse_parameter_file names the chain");
  }
  for (unsigned int n = 0; n <= max_include_depth; ++n)
    write("deep_" + std::to_string(n) + ".prm",
          n == max_include_depth ?
            "" :
            "include deep_" + std::to_string(n + 1) + ".prm\n");
  check(contains(error_of([] { outline_parameter_file("deep_0.prm"); }),
                 "nested deeper than 16 files"),
        "include depth limit");

  // a UTF-8 byte-order mark is skipped
  write("bom.prm",
        "\xEF\xBB\xBFset Dimension = 2\nsubsection Body 1\n"
        "  set Young's modulus = 5\nend\n");
  {
    dealii::ParameterHandler prm;
    declare(prm);
    check(
      error_of([&] { parse_parameter_file(prm, "bom.prm", false); }).empty() &&
        prm.get_integer("Dimension") == 2,
      "byte-order mark skipped");
    check(subsection_path_at_line("bom.prm", 3) == "Body 1",
          "byte-order mark: subsection path after it");
  }

  // subnormal and unparsable doubles name the parameter
  write("tiny.prm", "subsection Body 1\n  set Young's modulus = 1e-320\nend\n");
  {
    dealii::ParameterHandler prm;
    declare(prm);
    check(contains(error_of([&]
                            { parse_parameter_file(prm, "tiny.prm", false); }),
                   "The value `1e-320' (`set Young's modulus' in `subsection "
                   "Body 1') is too small for a double"),
          "1e-320 names the parameter");
  }

  // a 1 MB value is echoed cut to a few hundred bytes
  write("huge.prm",
        "subsection Body 1\n  set Name = " + std::string(1000000, 'c') +
          "\nend\n");
  {
    dealii::ParameterHandler prm;
    declare(prm);
    const std::string message =
      error_of([&] { parse_parameter_file(prm, "huge.prm", false); });
    check(contains(message, "ccc... (1000000 bytes)' does not match") &&
            message.size() < 2000,
          "a huge value is cut in the message (" +
            std::to_string(message.size()) + " bytes)");
  }
  check(shorten_for_message("abc", 2) == "ab... (3 bytes)" &&
          shorten_for_message("abc", 3) == "abc",
        "shorten_for_message");

  fs::current_path(root.parent_path());
  fs::remove_all(root);
  return test_tools::finish();
}
