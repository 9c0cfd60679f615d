#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <io/parameter_file.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    std::string
    parameter_location(const std::string &subsection_path,
                       const std::string &entry)
    {
      if (subsection_path.empty())
        return "(`set " + entry + "' at the top level)";
      return "(`set " + entry + "' in `subsection " + subsection_path + "')";
    }


    std::string
    join_path(const std::string &path, const std::string &subsection)
    {
      return path.empty() ? subsection : path + "/" + subsection;
    }


    std::string
    subsection_path_at_line(const std::string &file_name,
                            const unsigned int line_number)
    {
      std::ifstream            in(file_name);
      std::vector<std::string> stack;
      std::string              line;
      for (unsigned int n = 1; n < line_number && std::getline(in, line); ++n)
      {
        // strip comments and surrounding blanks, as ParameterHandler does
        const auto comment = line.find('#');
        if (comment != std::string::npos)
          line.erase(comment);
        line = dealii::Utilities::trim(line);
        if (line.rfind("subsection ", 0) == 0)
          stack.push_back(dealii::Utilities::trim(line.substr(11)));
        else if ((line == "end") && !stack.empty())
          stack.pop_back();
      }
      std::string path;
      for (const auto &name : stack)
        path = join_path(path, name);
      return path;
    }


    namespace
    {
      void
      print_json_level(const nlohmann::ordered_json &level,
                       const unsigned int            indent,
                       std::ostream                 &out)
      {
        const std::string prefix(indent, ' ');
        const auto        comment = [&](const std::string &text)
        {
          for (const auto &line :
               dealii::Utilities::break_text_into_lines(text, 76 - indent))
            out << prefix << "# " << line << "\n";
        };
        for (const auto &[name, entry] : level.items())
          if (entry.contains("value"))
          {
            comment(entry.value("documentation", std::string()));
            comment("Default: `" + entry.value("default_value", std::string()) +
                    "'. Allowed: " +
                    entry.value("pattern_description", std::string()));
            out << prefix << "set " << name << " = "
                << entry.value("value", std::string()) << "\n\n";
          }
        for (const auto &[name, entry] : level.items())
          if (!entry.contains("value"))
          {
            out << prefix << "subsection " << name << "\n";
            print_json_level(entry, indent + 2, out);
            out << prefix << "end\n\n";
          }
      }
    } // namespace


    void
    print_documented_parameters(const dealii::ParameterHandler &prm,
                                std::ostream                   &out)
    {
      std::stringstream json_text;
      prm.print_parameters(json_text,
                           dealii::ParameterHandler::JSON |
                             dealii::ParameterHandler::KeepDeclarationOrder);
      const auto json = nlohmann::ordered_json::parse(json_text.str());
      print_json_level(json, 0, out);
    }


    void
    parse_parameter_file(dealii::ParameterHandler &prm,
                         const std::string        &file_name,
                         const bool                skip_undefined)
    {
      {
        std::error_code error;
        AssertThrow(std::filesystem::is_regular_file(file_name, error) &&
                      std::ifstream(file_name),
                    dealii::ExcMessage("Cannot open the input file `" +
                                       file_name + "'."));
      }
      try
      {
        prm.parse_input(file_name, "", skip_undefined);
      }
      catch (const dealii::ExceptionBase &exception)
      {
        std::ostringstream info;
        exception.print_info(info);
        std::string text = info.str();
        // deal.II indents its messages; make them one tidy block
        text = std::regex_replace(text, std::regex("[ \t]*\n[ \t]*"), " ");
        text = dealii::Utilities::trim(text);

        std::smatch match;
        std::string where = "in the input file `" + file_name + "'";
        std::string path;
        if (std::regex_search(text,
                              match,
                              std::regex("Line <([0-9]+)> of file <.*?>?: *")))
        {
          const unsigned int line_number = std::stoul(match[1].str());
          path  = subsection_path_at_line(file_name, line_number);
          where = "in line " + std::to_string(line_number) +
                  " of the input file `" + file_name + "'";
          text = match.suffix().str();
        }
        // say it ASPECT style: name the entry and its subsection
        if (std::regex_search(text,
                              match,
                              std::regex(
                                "No entry with name <(.*)> was declared")))
          throw dealii::ExcMessage(
            "Unknown parameter " + parameter_location(path, match[1].str()) +
            " " + where +
            ": there is no such parameter in this subsection (see "
            "`dualcontact --print-parameters').");
        if (std::regex_search(
              text,
              match,
              std::regex(
                "The entry value <?(.*?)>? for the entry named <?(.*?)>? "
                "does not match the given pattern:? <?(.*?)>?\\.?$")))
          throw dealii::ExcMessage(
            "The value `" + match[1].str() + "' does not match the pattern " +
            match[3].str() + " " + parameter_location(path, match[2].str()) +
            " " + where + ".");
        if (std::regex_search(
              text,
              match,
              std::regex("There is no such subsection to be entered: (.*)")))
          throw dealii::ExcMessage(
            "Unknown subsection `subsection " +
            join_path(path, dealii::Utilities::trim(match[1].str())) + "' " +
            where +
            ". (Numbered subsections `Body N', `Material N', `Dirichlet "
            "N', `Traction N' exist for N up to the corresponding `Number "
            "of ...' parameter.)");
        if (!path.empty())
          where += " (in `subsection " + path + "')";
        throw dealii::ExcMessage("Error " + where + ": " + text);
      }
    }

    void
    for_each_numbered_subsection(
      dealii::ParameterHandler                                     &prm,
      const std::string                                            &name,
      const unsigned int                                            count,
      const std::string                                            &path,
      const std::function<void(unsigned int, const std::string &)> &action)
    {
      for (unsigned int k = 1; k <= count; ++k)
      {
        const std::string subsection = name + " " + std::to_string(k);
        prm.enter_subsection(subsection);
        try
        {
          action(k, join_path(path, subsection));
        }
        catch (...)
        {
          prm.leave_subsection();
          throw;
        }
        prm.leave_subsection();
      }
    }


    std::string
    ParameterOverride::subsection_path() const
    {
      std::string path;
      for (const auto &name : subsections)
        path = join_path(path, name);
      return path;
    }


    ParameterOverride
    parse_parameter_override(const std::string &text)
    {
      const auto equals = text.find('=');
      AssertThrow(equals != std::string::npos,
                  dealii::ExcMessage("The option `--set " + text +
                                     "' has no `=': expected --set "
                                     "\"Subsection/Entry=value\" (e.g. "
                                     "\"Body 1/Mesh/Global refinements=3\")."));
      ParameterOverride result;
      result.text  = text;
      result.value = dealii::Utilities::trim(text.substr(equals + 1));
      std::vector<std::string> names =
        dealii::Utilities::split_string_list(text.substr(0, equals), '/');
      AssertThrow(!names.empty() && !names.back().empty(),
                  dealii::ExcMessage("The option `--set " + text +
                                     "' names no parameter before the `=': "
                                     "expected --set "
                                     "\"Subsection/Entry=value\"."));
      result.entry = names.back();
      names.pop_back();
      result.subsections = names;
      return result;
    }


    void
    apply_parameter_overrides(dealii::ParameterHandler             &prm,
                              const std::vector<ParameterOverride> &overrides,
                              const bool skip_undefined)
    {
      for (const auto &entry : overrides)
      {
        const std::string where = "given by `--set " + entry.text + "'";
        if (!prm.subsection_path_exists(entry.subsections))
        {
          if (skip_undefined)
            continue;
          AssertThrow(false,
                      dealii::ExcMessage(
                        "Unknown subsection `subsection " +
                        entry.subsection_path() + "' " + where +
                        " (see `dualcontact --print-parameters'; numbered "
                        "subsections `Body N', ... exist for N up to their "
                        "`Number of ...')."));
        }
        // as a `set' line of a file: deal.II checks the value against the
        // entry's pattern exactly as when it reads one
        std::string input;
        for (const auto &name : entry.subsections)
          input += "subsection " + name + "\n";
        input += "set " + entry.entry + " = " + entry.value + "\n";
        for (std::size_t k = 0; k < entry.subsections.size(); ++k)
          input += "end\n";
        try
        {
          prm.parse_input_from_string(input, "", skip_undefined);
        }
        catch (const dealii::ExceptionBase &exception)
        {
          std::ostringstream info;
          exception.print_info(info);
          const std::string text = info.str();
          const std::string location =
            parameter_location(entry.subsection_path(), entry.entry);
          if (text.find("No entry with name") != std::string::npos)
            throw dealii::ExcMessage(
              "Unknown parameter " + location + " " + where +
              ": there is no such parameter in this subsection (see "
              "`dualcontact --print-parameters').");
          std::smatch match;
          if (std::regex_search(text,
                                match,
                                std::regex("does not match the given "
                                           "pattern:?[ \t\n]*<?([^\n>]*)")))
            throw dealii::ExcMessage("The value `" + entry.value +
                                     "' does not match the pattern " +
                                     dealii::Utilities::trim(match[1].str()) +
                                     " " + location + " " + where + ".");
          throw dealii::ExcMessage(
            "Cannot set " + location + " " + where + ": " +
            std::regex_replace(dealii::Utilities::trim(text),
                               std::regex("[ \t]*\n[ \t]*"),
                               " "));
        }
      }
    }
  } // namespace io
} // namespace dualcontact
