#pragma once

#include <deal.II/base/parameter_handler.h>

#include <cstddef>
#include <functional>
#include <ostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    /**
     * "(`set Young's modulus' in `subsection Body 1/Material 2')": where a
     * parameter lives, for error messages (ASPECT style).  An empty
     * @p subsection_path means the top level.
     */
    std::string
    parameter_location(const std::string &subsection_path,
                       const std::string &entry);

    /** "Body 1" + "Material 2" -> "Body 1/Material 2". */
    std::string
    join_path(const std::string &path, const std::string &subsection);

    /**
     * "0, 3, 7" (or "none" for an empty list): the ids a mesh or a scene has,
     * for error messages that tell the user what would have been valid.
     */
    template <typename Number>
    std::string
    join_numbers(const std::vector<Number> &numbers)
    {
      std::string text;
      for (const auto number : numbers)
        text += (text.empty() ? "" : ", ") + std::to_string(number);
      return text.empty() ? "none" : text;
    }

    /**
     * Run @p action inside `subsection NAME 1', ..., `subsection NAME
     * count' of @p prm, passing k (1-based) and the subsection's full path
     * below @p path (for parameter_location()).  Scenes describe their
     * bodies, materials and conditions as such numbered subsections, whose
     * number is only known after an earlier pass (see
     * driver::SceneParameters::read()); this keeps the enter/leave pairing
     * and the naming in one place for declaring and for parsing.
     */
    void
    for_each_numbered_subsection(
      dealii::ParameterHandler                                     &prm,
      const std::string                                            &name,
      const unsigned int                                            count,
      const std::string                                            &path,
      const std::function<void(unsigned int, const std::string &)> &action);

    /**
     * Read @p file_name into @p prm.  With @p skip_undefined, entries and
     * subsections that are not declared are ignored (used by the passes that
     * only read how many bodies, materials, ... a scene has).
     *
     * A missing file and every parse error of deal.II's ParameterHandler
     * (unknown entry or subsection, value outside its pattern, unbalanced
     * `end') are rethrown as an ExcMessage that names the file, the line and
     * the subsection the line is in.  Before deal.II reads it, the file is
     * checked by outline_parameter_file() (duplicate entries, include
     * cycles); a UTF-8 byte-order mark is skipped; afterwards
     * check_double_entries() rejects values no double holds.  Values echoed
     * in messages are cut by shorten_for_message().
     */
    void
    parse_parameter_file(dealii::ParameterHandler &prm,
                         const std::string        &file_name,
                         const bool                skip_undefined);

    /**
     * What a parameter file writes, found by reading its lines (and those of
     * the files it includes) independently of deal.II's ParameterHandler,
     * which only keeps the values and not whether a subsection or an entry
     * appeared in the file at all.
     */
    struct ParameterFileOutline
    {
      /** Every subsection path the file opens ("Body 1", "Body 1/Mesh"). */
      std::set<std::string> subsections;
      /** Every entry the file sets: (subsection path, entry name). */
      std::set<std::pair<std::string, std::string>> entries;
    };

    /**
     * The deepest chain of `include' lines a parameter file may have: a
     * deeper one is an error (it is an include cycle in practice, but also
     * catches those that go through differently spelled paths).
     */
    constexpr unsigned int max_include_depth = 16;

    /**
     * Read @p file_name line by line, following `include' (relative to the
     * working directory, as deal.II does), and throw an ExcMessage on what
     * deal.II's ParameterHandler would otherwise accept silently or not
     * survive:
     * - an entry set twice in the same subsection of the same file (the
     *   last value would win unnoticed); an entry of an included file may be
     *   set again by the including file (that is what including a base
     *   file is for);
     * - a file that includes itself, directly or through others (deal.II
     *   recurses until the stack overflows), or includes deeper than
     *   max_include_depth: the message lists the chain of files.
     * - a line whose text (without its comment) is not UTF-8: the message
     *   names the file, the line and, for a value, the entry (deal.II
     *   would keep the bytes, which the JSON round trip of
     *   check_double_entries() cannot parse); comments may hold any bytes.
     * A UTF-8 byte-order mark at the start of a file is skipped.
     */
    ParameterFileOutline
    outline_parameter_file(const std::string &file_name);

    /**
     * Throw an ExcMessage naming the parameter if the value of an entry whose
     * pattern is a Double does not convert to a normal finite double:
     * deal.II's pattern accepts a subnormal such as 1e-320, whose conversion
     * later fails with "Can't convert <1e-320> to a double." and no name.
     */
    void
    check_double_entries(const dealii::ParameterHandler &prm);

    /**
     * @p text for an error message: at most @p max_bytes bytes of it, and
     * when it was longer, "... (N bytes)" after them, so that a huge value
     * is not echoed whole.
     */
    std::string
    shorten_for_message(const std::string &text,
                        const std::size_t  max_bytes = 200);

    /**
     * One `--set "Subsection/Entry=value"' of the command line: the
     * subsections (nested with '/'), the entry and its value, and the
     * text as given (for error messages).
     */
    struct ParameterOverride
    {
      std::vector<std::string> subsections;
      std::string              entry;
      std::string              value;
      std::string              text;

      /** "Body 1/Mesh": the subsections joined, empty at the top level. */
      std::string
      subsection_path() const;
    };

    /**
     * Split @p text ("Body 1/Mesh/Global refinements=3") at its first '='
     * and the part before it at '/'; blanks around the names and the value
     * are dropped.  Throws an ExcMessage naming @p text if it has no '=' or
     * no entry name.
     */
    ParameterOverride
    parse_parameter_override(const std::string &text);

    /**
     * Set the values of @p overrides in @p prm, in order, as if they were
     * `set' lines at the end of the parameter file: the values are checked
     * against their patterns as file values are.  With @p skip_undefined,
     * overrides of entries or subsections that @p prm does not declare are
     * ignored (the passes of driver::SceneParameters::read() that only read
     * the layout); without, an unknown subsection or entry and a value that
     * does not match its pattern throw an ExcMessage naming the entry, its
     * subsection and the `--set' argument.
     */
    void
    apply_parameter_overrides(dealii::ParameterHandler             &prm,
                              const std::vector<ParameterOverride> &overrides,
                              const bool skip_undefined);

    /**
     * Print every entry of @p prm as a parameter file: per entry its
     * documentation, its default value and its pattern as comments, then
     * `set Name = value'; entries before subsections, in declaration order.
     */
    void
    print_documented_parameters(const dealii::ParameterHandler &prm,
                                std::ostream                   &out);

    /**
     * The subsection path ("Body 1/Mesh") in effect at line @p line_number
     * (1-based) of the parameter file @p file_name.
     */
    std::string
    subsection_path_at_line(const std::string &file_name,
                            const unsigned int line_number);
  } // namespace io
} // namespace dualcontact
