#pragma once

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <ostream>
#include <string>
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
     * the subsection the line is in.
     */
    void
    parse_parameter_file(dealii::ParameterHandler &prm,
                         const std::string        &file_name,
                         const bool                skip_undefined);

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
