#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <io/parameter_file.h>

#include <nlohmann/json.hpp>

#include <cctype>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
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
    shorten_for_message(const std::string &text, const std::size_t max_bytes)
    {
      if (text.size() <= max_bytes)
        return text;
      return text.substr(0, max_bytes) + "... (" + std::to_string(text.size()) +
             " bytes)";
    }


    namespace
    {
      const std::string utf8_byte_order_mark = "\xEF\xBB\xBF";

      std::string
      without_byte_order_mark(const std::string &line)
      {
        return line.rfind(utf8_byte_order_mark, 0) == 0 ?
                 line.substr(utf8_byte_order_mark.size()) :
                 line;
      }

      /**
       * Where @p text stops being UTF-8: the offset of the first byte that
       * does not begin or continue a well-formed sequence (an overlong form,
       * a surrogate and a code point beyond U+10FFFF are not well formed),
       * std::string::npos if it is UTF-8 throughout.
       */
      std::size_t
      first_non_utf8_byte(const std::string &text)
      {
        const auto byte = [&](const std::size_t i)
        { return static_cast<unsigned char>(text[i]); };
        std::size_t i = 0;
        while (i < text.size())
        {
          const unsigned char lead = byte(i);
          std::size_t         n    = 0; // continuation bytes that follow
          unsigned char       low = 0x80, high = 0xBF; // of the second byte
          if (lead < 0x80)
            n = 0;
          else if (lead >= 0xC2 && lead <= 0xDF)
            n = 1;
          else if (lead >= 0xE0 && lead <= 0xEF)
          {
            n = 2;
            if (lead == 0xE0)
              low = 0xA0; // overlong
            else if (lead == 0xED)
              high = 0x9F; // surrogates
          }
          else if (lead >= 0xF0 && lead <= 0xF4)
          {
            n = 3;
            if (lead == 0xF0)
              low = 0x90; // overlong
            else if (lead == 0xF4)
              high = 0x8F; // beyond U+10FFFF
          }
          else
            return i;
          if (n > 0 && i + n >= text.size()) // cut short
            return i;
          for (std::size_t k = 1; k <= n; ++k)
          {
            const unsigned char next = byte(i + k);
            if (next < (k == 1 ? low : 0x80) || next > (k == 1 ? high : 0xBF))
              return i;
          }
          i += n + 1;
        }
        return std::string::npos;
      }

      std::string
      hex_byte(const char c)
      {
        static const char digits[] = "0123456789ABCDEF";
        const auto        b        = static_cast<unsigned char>(c);
        return std::string("0x") + digits[b >> 4] + digits[b & 0xF];
      }

      /** deal.II's comment rule: `#' starts one unless written `\#'. */
      std::string
      without_comment(const std::string &line)
      {
        for (std::size_t i = 0; i < line.size(); ++i)
          if (line[i] == '#' && (i == 0 || line[i - 1] != '\\'))
            return line.substr(0, i);
        return line;
      }

      /**
       * deal.II's message with every word (the values it echoes) longer than
       * 200 bytes cut by shorten_for_message(), and the whole cut to 4000
       * bytes, before the regular expressions below see it (std::regex
       * recurses per character: a 10 MB value would overflow the stack).
       */
      std::string
      with_short_values(const std::string &text)
      {
        std::string result;
        std::size_t position = 0;
        while (position < text.size())
        {
          const std::size_t end =
            std::min(text.find_first_of(" \t\n", position), text.size());
          result += shorten_for_message(text.substr(position, end - position));
          if (end < text.size())
            result += text[end];
          position = end + 1;
        }
        return shorten_for_message(result, 4000);
      }

      /** deal.II's keywords: `set ' or `SET ', `subsection ' or ... */
      bool
      starts_with_keyword(const std::string &text, const std::string &keyword)
      {
        std::string upper = keyword;
        for (auto &c : upper)
          c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        return text.rfind(keyword, 0) == 0 || text.rfind(upper, 0) == 0;
      }


      /**
       * Throw naming the file, the line and, for a `set' line whose value
       * holds it, the entry: @p text (line @p line of @p file_name, in the
       * subsection @p path, without its comment) has a byte that is not
       * UTF-8 at @p bad.  deal.II would take the bytes as they are, but the
       * parameter check's JSON round trip (check_double_entries()) and every
       * file that echoes parameters (used_parameters.prm, statistics.json)
       * need UTF-8.
       */
      [[noreturn]] void
      throw_non_utf8(const std::string &file_name,
                     const unsigned int line,
                     const std::string &path,
                     const std::string &text,
                     const std::size_t  bad)
      {
        const std::string where =
          "`" + file_name + "', line " + std::to_string(line);
        const std::string advice =
          ": save the file as UTF-8 (only comments may hold other bytes).";
        const auto equals = text.find('=');
        if (starts_with_keyword(text, "set ") && equals != std::string::npos &&
            bad > equals)
        {
          const std::string entry =
            dealii::Utilities::trim(text.substr(4, equals - 4));
          const std::size_t value_start =
            text.find_first_not_of(" \t", equals + 1);
          throw dealii::ExcMessage(
            where + ", entry `" + entry + "' " +
            (path.empty() ? std::string("at the top level") :
                            "in `subsection " + path + "'") +
            ": the value is not valid UTF-8 (byte " + hex_byte(text[bad]) +
            " at position " + std::to_string(bad - value_start + 1) +
            " of the value)" + advice);
        }
        throw dealii::ExcMessage(
          where + ": the line is not valid UTF-8 (byte " + hex_byte(text[bad]) +
          " at position " + std::to_string(bad + 1) +
          " of the line without its comment)" + advice);
      }

      /** Where an entry was set: file and line, for the duplicate message. */
      struct EntrySite
      {
        std::string  file;
        unsigned int line;
      };

      /**
       * The state of outline_parameter_file(): the outline so far, the
       * entries set per subsection path and the chain of files being read.
       */
      struct OutlineReader
      {
        ParameterFileOutline                                     outline;
        std::map<std::pair<std::string, std::string>, EntrySite> entries;
        std::vector<std::string>                                 chain;

        std::string
        chain_text() const
        {
          std::string text;
          for (const auto &file : chain)
            text += (text.empty() ? "`" : " includes `") + file + "'";
          return text;
        }

        void
        read(const std::string &file_name, std::vector<std::string> &stack);
      };


      void
      OutlineReader::read(const std::string        &file_name,
                          std::vector<std::string> &stack)
      {
        std::error_code   error;
        const std::string canonical =
          std::filesystem::weakly_canonical(file_name, error).string();
        for (const auto &outer : chain)
          AssertThrow(outer != canonical,
                      dealii::ExcMessage("The input file `" + file_name +
                                         "' includes itself: " + chain_text() +
                                         " includes `" + file_name +
                                         "'. Remove the `include' that closes "
                                         "the cycle."));
        AssertThrow(chain.size() < max_include_depth,
                    dealii::ExcMessage("`include' is nested deeper than " +
                                       std::to_string(max_include_depth) +
                                       " files: " + chain_text() +
                                       " includes `" + file_name + "'."));
        std::ifstream in(file_name);
        if (!in)
          return; // deal.II names the missing file in its own message
        chain.push_back(canonical);

        std::string  line;
        std::string  logical_line;
        unsigned int line_number = 0;
        unsigned int first_line  = 1;
        while (std::getline(in, line))
        {
          ++line_number;
          if (line_number == 1)
            line = without_byte_order_mark(line);
          if (logical_line.empty())
            first_line = line_number;
          // a line ending in a backslash continues on the next one
          const std::string trimmed = dealii::Utilities::trim(line);
          if (!trimmed.empty() && trimmed.back() == '\\')
          {
            logical_line += trimmed.substr(0, trimmed.size() - 1);
            continue;
          }
          logical_line += line;
          const std::string text =
            dealii::Utilities::trim(without_comment(logical_line));
          logical_line.clear();

          std::string path;
          for (const auto &name : stack)
            path = join_path(path, name);
          if (const std::size_t bad = first_non_utf8_byte(text);
              bad != std::string::npos)
            throw_non_utf8(file_name, first_line, path, text, bad);
          if (starts_with_keyword(text, "subsection "))
          {
            stack.push_back(dealii::Utilities::trim(text.substr(11)));
            outline.subsections.insert(join_path(path, stack.back()));
          }
          else if ((text == "end" || text == "END") && !stack.empty())
            stack.pop_back();
          else if (starts_with_keyword(text, "include "))
            read(dealii::Utilities::trim(text.substr(8)), stack);
          else if (starts_with_keyword(text, "set ") &&
                   text.find('=') != std::string::npos)
          {
            const std::string entry =
              dealii::Utilities::trim(text.substr(4, text.find('=') - 4));
            const auto [site, inserted] =
              entries.emplace(std::make_pair(path, entry),
                              EntrySite{file_name, first_line});
            // a file may override what a file it includes sets
            AssertThrow(inserted || site->second.file != file_name,
                        dealii::ExcMessage(
                          "The parameter " + parameter_location(path, entry) +
                          " is set twice in the input file `" + file_name +
                          "', in line " + std::to_string(site->second.line) +
                          " and in line " + std::to_string(first_line) +
                          ": only one value can hold; remove one of them."));
            site->second = EntrySite{file_name, first_line};
            outline.entries.emplace(path, entry);
          }
        }
        chain.pop_back();
      }


      /**
       * Call @p action(path, entry name, value, pattern description) for
       * every entry of the JSON tree of a ParameterHandler.
       */
      void
      for_each_entry(const nlohmann::json                           &level,
                     const std::string                              &path,
                     const std::function<void(const std::string &,
                                              const std::string &,
                                              const std::string &,
                                              const std::string &)> &action)
      {
        for (const auto &[name, entry] : level.items())
        {
          const std::string demangled = dealii::Utilities::trim(name);
          if (entry.contains("value"))
            action(path,
                   demangled,
                   entry.value("value", std::string()),
                   entry.value("pattern_description", std::string()));
          else if (entry.is_object())
            for_each_entry(entry, join_path(path, demangled), action);
        }
      }


      /** Throw naming the entry unless @p text is a normal finite double. */
      void
      check_double(const std::string &text,
                   const std::string &path,
                   const std::string &entry)
      {
        const std::string trimmed = dealii::Utilities::trim(text);
        char             *end     = nullptr;
        errno                     = 0;
        const double number       = std::strtod(trimmed.c_str(), &end);
        AssertThrow(!trimmed.empty() && *end == '\0' && std::isfinite(number),
                    dealii::ExcMessage("The value `" +
                                       shorten_for_message(trimmed) +
                                       "' is not a finite number " +
                                       parameter_location(path, entry) + "."));
        AssertThrow(errno != ERANGE || number == 0.,
                    dealii::ExcMessage(
                      "The value `" + shorten_for_message(trimmed) + "' " +
                      parameter_location(path, entry) +
                      " is too small for a double (its magnitude is below " +
                      dealii::Utilities::to_string(DBL_MIN) +
                      "): write 0 or a value of larger magnitude."));
      }
    } // namespace


    ParameterFileOutline
    outline_parameter_file(const std::string &file_name)
    {
      OutlineReader            reader;
      std::vector<std::string> stack;
      reader.read(file_name, stack);
      return reader.outline;
    }


    void
    check_double_entries(const dealii::ParameterHandler &prm)
    {
      std::stringstream json_text;
      prm.print_parameters(json_text, dealii::ParameterHandler::JSON);
      nlohmann::json tree;
      try
      {
        tree = nlohmann::json::parse(json_text.str());
      }
      catch (const nlohmann::json::exception &)
      {
        // the files and `--set' options are checked for UTF-8 as they are
        // read (outline_parameter_file(), apply_parameter_overrides()):
        // only a value set otherwise gets here
        AssertThrow(false,
                    dealii::ExcMessage(
                      "A parameter value is not valid UTF-8: give the "
                      "parameters in UTF-8."));
      }
      for_each_entry(tree,
                     "",
                     [](const std::string &path,
                        const std::string &entry,
                        const std::string &value,
                        const std::string &pattern)
                     {
                       if (pattern.rfind("[Double", 0) == 0)
                         check_double(value, path, entry);
                       else if (pattern.rfind("[List of <[Double", 0) == 0)
                         for (const auto &item :
                              dealii::Utilities::split_string_list(value))
                           check_double(item, path, entry);
                     });
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
        if (n == 1)
          line = without_byte_order_mark(line);
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
      (void)outline_parameter_file(file_name);
      try
      {
        std::ifstream in(file_name);
        std::string   first_line;
        std::getline(in, first_line);
        if (first_line.rfind(utf8_byte_order_mark, 0) == 0)
        {
          // deal.II would take the mark for part of line 1
          std::stringstream text;
          text << without_byte_order_mark(first_line) << '\n' << in.rdbuf();
          prm.parse_input(text, file_name, "", skip_undefined);
        }
        else
          prm.parse_input(file_name, "", skip_undefined);
      }
      catch (const dealii::ExceptionBase &exception)
      {
        std::ostringstream info;
        exception.print_info(info);
        std::string text = with_short_values(info.str());
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
        {
          // deal.II names it with the enclosing path, joined by `.'
          std::string       name = dealii::Utilities::trim(match[1].str());
          const std::string dotted =
            std::regex_replace(path, std::regex("/"), ".");
          if (!dotted.empty() && name.rfind(dotted + ".", 0) == 0)
            name = name.substr(dotted.size() + 1);
          throw dealii::ExcMessage(
            "Unknown subsection `subsection " + join_path(path, name) + "' " +
            where +
            ". (Numbered subsections `Body N', `Material N', `Dirichlet "
            "N', `Traction N' exist for N up to the corresponding `Number "
            "of ...' parameter.)");
        }
        if (!path.empty())
          where += " (in `subsection " + path + "')";
        throw dealii::ExcMessage("Error " + where + ": " +
                                 shorten_for_message(text, 400));
      }
      check_double_entries(prm);
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
        if (const std::size_t bad = first_non_utf8_byte(entry.text);
            bad != std::string::npos)
        {
          const bool in_value =
            first_non_utf8_byte(entry.subsection_path() + entry.entry) ==
            std::string::npos;
          throw dealii::ExcMessage(
            "The option `--set' " +
            (in_value ?
               "of " +
                 parameter_location(entry.subsection_path(), entry.entry) +
                 " gives a value that" :
               std::string("names a parameter that")) +
            " is not valid UTF-8 (byte " + hex_byte(entry.text[bad]) +
            "): give it in UTF-8.");
        }
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
