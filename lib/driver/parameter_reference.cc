#include <deal.II/base/exceptions.h>

#include <driver/parameter_reference.h>
#include <driver/scene_parameters.h>
#include <io/parameter_file.h>

#include <nlohmann/json.hpp>

#include <sstream>

namespace dualcontact
{
  namespace driver
  {
    namespace
    {
      /**
       * deal.II's JSON tree of one subsection (entries are the objects with
       * a "value") as {entries: [...], subsections: [...]}: arrays, so that
       * any reader keeps the declaration order.
       */
      nlohmann::ordered_json
      reference_of_level(const nlohmann::ordered_json &level)
      {
        nlohmann::ordered_json entries     = nlohmann::ordered_json::array();
        nlohmann::ordered_json subsections = nlohmann::ordered_json::array();
        for (const auto &[name, item] : level.items())
          if (item.contains("value"))
            entries.push_back(
              {{"name", name},
               {"default", item.value("default_value", std::string())},
               {"pattern", item.value("pattern_description", std::string())},
               {"documentation", item.value("documentation", std::string())}});
        for (const auto &[name, item] : level.items())
          if (!item.contains("value"))
          {
            nlohmann::ordered_json       subsection = {{"name", name}};
            const nlohmann::ordered_json inner      = reference_of_level(item);
            subsection["entries"]                   = inner["entries"];
            subsection["subsections"]               = inner["subsections"];
            subsections.push_back(subsection);
          }
        return {{"entries", entries}, {"subsections", subsections}};
      }

      /**
       * The numbered subsections of the representative layout and what
       * they stand for (SceneParameters and BodyParameters declare them).
       */
      nlohmann::ordered_json
      repeated_subsections()
      {
        const auto repeated = [](const std::string &declared,
                                 const std::string &stands_for,
                                 const std::string &count)
        {
          return nlohmann::ordered_json{{"declared", declared},
                                        {"stands_for", stands_for},
                                        {"count", count}};
        };
        return nlohmann::ordered_json::array(
          {repeated("Body 1", "Body N", "Number of bodies"),
           repeated("Body 1/Material 1",
                    "Body N/Material M",
                    "Body N/Number of materials"),
           repeated("Body 1/Dirichlet 1",
                    "Body N/Dirichlet M",
                    "Body N/Number of Dirichlet conditions"),
           repeated("Body 1/Traction 1",
                    "Body N/Traction M",
                    "Body N/Number of traction conditions"),
           repeated("Obstacle 1", "Obstacle N", "Number of obstacles"),
           repeated("Contact pair 1",
                    "Contact pair N",
                    "Number of contact pairs")});
      }
    } // namespace


    ParameterReference::Format
    ParameterReference::parse_format(const std::string &name)
    {
      if (name == "prm")
        return Format::prm;
      if (name == "json")
        return Format::json;
      AssertThrow(false,
                  dealii::ExcMessage("Unknown format `" + name +
                                     "' of --print-parameters (known: prm, "
                                     "json)."));
      return Format::prm;
    }


    SceneLayout
    ParameterReference::representative_layout()
    {
      SceneLayout layout;
      layout.dimension       = 3;
      layout.bodies          = {BodyLayout()};
      layout.n_obstacles     = 1;
      layout.n_contact_pairs = 1;
      return layout;
    }


    void
    ParameterReference::print(std::ostream &out, const Format format)
    {
      dealii::ParameterHandler prm;
      SceneParameters::declare_parameters(prm, representative_layout());
      if (format == Format::json)
        print_json(prm, out);
      else
        print_prm(prm, out);
    }


    void
    ParameterReference::print_prm(const dealii::ParameterHandler &prm,
                                  std::ostream                   &out)
    {
      out << "# dualcontact " << DUALCONTACT_VERSION
          << ": all parameters, with documentation, default "
             "and allowed values.\n# Shown for one body, one "
             "obstacle and one contact pair; `Body 2', `Obstacle "
             "2', `Contact pair 2', ... have the same entries.\n\n";
      io::print_documented_parameters(prm, out);
    }


    void
    ParameterReference::print_json(const dealii::ParameterHandler &prm,
                                   std::ostream                   &out)
    {
      std::stringstream json_text;
      prm.print_parameters(json_text,
                           dealii::ParameterHandler::JSON |
                             dealii::ParameterHandler::KeepDeclarationOrder);
      nlohmann::ordered_json reference;
      reference["program"]              = "dualcontact";
      reference["version"]              = DUALCONTACT_VERSION;
      reference["dimension"]            = representative_layout().dimension;
      reference["repeated_subsections"] = repeated_subsections();
      reference["parameters"] =
        reference_of_level(nlohmann::ordered_json::parse(json_text.str()));
      out << reference.dump(1) << '\n';
    }
  } // namespace driver
} // namespace dualcontact
