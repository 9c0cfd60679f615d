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
#include <utility>
#include <vector>

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
    prm.declare_entry("Title", "", dealii::Patterns::Anything());
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

  // bytes that are not UTF-8 (issue 49): a value is refused naming the
  // file, the line and the entry, any other line naming the line; comments
  // keep any bytes; UTF-8 of two, three and four bytes is taken as it is
  {
    const auto error_of_file =
      [](const std::string &name, const std::string &text)
    {
      write(name, text);
      dealii::ParameterHandler prm;
      declare(prm);
      return error_of([&] { parse_parameter_file(prm, name, false); });
    };
    check(contains(error_of_file("latin1.prm",
                                 "set Dimension = 2\nsubsection Body 1\n"
                                 "  set Name = a\xE9\xFF\nend\n"),
                   "`latin1.prm', line 3, entry `Name' in `subsection Body "
                   "1': the value is not valid UTF-8 (byte 0xE9 at position "
                   "2 of the value)"),
          "non-UTF-8 value: file, line, entry and byte named");
    check(error_of_file("comment.prm",
                        "set Dimension = 2 # caf\xE9\xFF\n# \xC0\n")
            .empty(),
          "non-UTF-8 bytes in comments are kept");
    check(error_of_file("utf8.prm",
                        "set Title = caf\xC3\xA9 \xE2\x82\xAC "
                        "\xF0\x9F\x98\x80\n")
            .empty(),
          "UTF-8 of 2, 3 and 4 bytes is taken");
    for (const auto &[bytes, what] :
         std::vector<std::pair<std::string, std::string>>{
           {"\xC0\xAF", "overlong"},
           {"\xED\xA0\x80", "surrogate"},
           {"\xF4\x90\x80\x80", "beyond U+10FFFF"},
           {"\xE2\x82", "cut short"},
           {"\x80", "lone continuation byte"}})
      check(contains(error_of_file("bad_utf8.prm",
                                   "set Title = x" + bytes + "\n"),
                     "line 1, entry `Title' at the top level: the value is "
                     "not valid UTF-8 (byte 0x"),
            "refused: " + what);
    check(contains(error_of_file("line.prm",
                                 "set Dimension = 2\n\xFF\xFE junk\n"),
                   "`line.prm', line 2: the line is not valid UTF-8 (byte "
                   "0xFF at position 1"),
          "a line of bytes: the line named");
    dealii::ParameterHandler prm;
    declare(prm);
    check(contains(error_of(
                     [&]
                     {
                       apply_parameter_overrides(
                         prm, {parse_parameter_override("Title=a\xE9")}, false);
                     }),
                   "The option `--set' of (`set Title' at the top level) "
                   "gives a value that is not valid UTF-8 (byte 0xE9)"),
          "--set with a non-UTF-8 value: the entry named");
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
