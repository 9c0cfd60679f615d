#include <deal.II/base/exceptions.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <driver/body_parameters.h>
#include <io/function_expression.h>
#include <io/parameter_file.h>

#include <algorithm>
#include <set>
#include <sstream>

namespace dualcontact
{
  namespace driver
  {
    namespace
    {
      std::string
      all_components(const unsigned int dim)
      {
        return dim == 2 ? "x, y" : "x, y, z";
      }

      /**
       * `Foo 1' is declared even when `Number of foos' is 0; it must then be
       * left at its defaults.
       */
      void
      check_unused_subsection(
        dealii::ParameterHandler                               &prm,
        const std::string                                      &subsection,
        const std::string                                      &count_entry,
        const std::string                                      &path,
        const std::vector<std::pair<std::string, std::string>> &defaults)
      {
        prm.enter_subsection(subsection);
        for (const auto &[entry, value] : defaults)
          AssertThrow(prm.get(entry) == value,
                      dealii::ExcMessage(
                        "`subsection " + io::join_path(path, subsection) +
                        "' sets `" + entry + "', but `" + count_entry +
                        "' is 0 " + io::parameter_location(path, count_entry) +
                        ": set it to the number of such subsections."));
        prm.leave_subsection();
      }

      constexpr double min_youngs_modulus = 1e-20;
      constexpr double max_youngs_modulus = 1e20;
    } // namespace


    template <int dim>
    void
    BodyParameters<dim>::declare_layout_entries(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Number of materials",
                        "1",
                        dealii::Patterns::Integer(1, 1000),
                        "Number of material regions of this body, each "
                        "described by a subsection `Material 1', `Material "
                        "2', ...");
      prm.declare_entry("Number of Dirichlet conditions",
                        "0",
                        dealii::Patterns::Integer(0, 1000),
                        "Number of prescribed-displacement conditions, each "
                        "a subsection `Dirichlet 1', `Dirichlet 2', ...");
      prm.declare_entry("Number of traction conditions",
                        "0",
                        dealii::Patterns::Integer(0, 1000),
                        "Number of surface-traction conditions, each a "
                        "subsection `Traction 1', `Traction 2', ...");
    }


    template <int dim>
    BodyLayout
    BodyParameters<dim>::parse_layout(dealii::ParameterHandler &prm)
    {
      BodyLayout layout;
      layout.n_materials = prm.get_integer("Number of materials");
      layout.n_dirichlet = prm.get_integer("Number of Dirichlet conditions");
      layout.n_tractions = prm.get_integer("Number of traction conditions");
      return layout;
    }


    template <int dim>
    void
    BodyParameters<dim>::declare_parameters(dealii::ParameterHandler &prm,
                                            const BodyLayout         &layout)
    {
      declare_layout_entries(prm);
      io::MeshGenerator<dim>::declare_parameters(prm);
      io::Placement<dim>::declare_parameters(prm);

      io::for_each_numbered_subsection(
        prm,
        "Material",
        layout.n_materials,
        "",
        [&](const unsigned int m, const std::string &)
        {
          prm.declare_entry("Material id",
                            std::to_string(m - 1),
                            dealii::Patterns::Integer(0, 65535),
                            "The cells with this material id (generated "
                            "meshes: 0; Gmsh: the physical tag of the cell) "
                            "are made of this material.");
          prm.declare_entry("Young's modulus",
                            "210e9",
                            dealii::Patterns::Double(),
                            "Young's modulus E [Pa], > 0 and within [1e-20, "
                            "1e20].");
          prm.declare_entry("Poisson's ratio",
                            "0.3",
                            dealii::Patterns::Double(),
                            "Poisson's ratio nu [-], in (-1, 0.5). In 2D the "
                            "body is in plane strain.");
        });

      io::for_each_numbered_subsection(
        prm,
        "Dirichlet",
        std::max(layout.n_dirichlet, 1u),
        "",
        [&](unsigned int, const std::string &)
        {
          prm.declare_entry("Boundary id",
                            "0",
                            dealii::Patterns::Integer(0, 65535),
                            "The boundary id of the faces where the "
                            "displacement is prescribed.");
          prm.declare_entry("Components",
                            all_components(dim),
                            dealii::Patterns::MultipleSelection(
                              dim == 2 ? "x|y" : "x|y|z"),
                            "The displacement components that are prescribed "
                            "(the others are free), e.g. `x, y' or `y'.");
          prm.declare_entry("Displacement",
                            io::zero_expressions(dim),
                            dealii::Patterns::Anything(),
                            "The prescribed displacement [m]: dim "
                            "expressions separated by `;' (one per "
                            "component; those not selected in `Components' "
                            "are ignored), functions of the placed position "
                            "x, y(, z) [m] and of the time t of a load step "
                            "(`subsection Load steps'; t = 1 without); the "
                            "constant pi is known.");
        });

      io::for_each_numbered_subsection(
        prm,
        "Traction",
        std::max(layout.n_tractions, 1u),
        "",
        [&](unsigned int, const std::string &)
        {
          prm.declare_entry("Boundary id",
                            "1",
                            dealii::Patterns::Integer(0, 65535),
                            "The boundary id of the faces that carry the "
                            "traction.");
          prm.declare_entry("Traction",
                            io::zero_expressions(dim),
                            dealii::Patterns::Anything(),
                            "Surface traction t [N/m^2] (force per unit area "
                            "of the undeformed surface, in global "
                            "coordinates): dim expressions separated by `;', "
                            "functions of the placed position x, y(, z) "
                            "[m] and of the load step's time t; the "
                            "constant pi is known.");
        });

      prm.declare_entry("Body force",
                        io::zero_expressions(dim),
                        dealii::Patterns::Anything(),
                        "Body force b [N/m^3] (e.g. density times gravity: "
                        "`0; 0; -7850*9.81'): dim expressions separated by "
                        "`;', functions of the placed position x, y(, z) "
                        "[m] and of the load step's time t.");
    }


    template <int dim>
    void
    BodyParameters<dim>::parse_parameters(
      dealii::ParameterHandler &prm,
      const std::string        &path,
      const std::string        &parameter_file_folder)
    {
      path_                   = path;
      name                    = path;
      const BodyLayout layout = parse_layout(prm);

      mesh.parse_parameters(prm, path, parameter_file_folder);
      placement.parse_parameters(prm, path);

      materials.clear();
      io::for_each_numbered_subsection(
        prm,
        "Material",
        layout.n_materials,
        path,
        [&](unsigned int, const std::string &sub_path)
        {
          const auto id = static_cast<dealii::types::material_id>(
            prm.get_integer("Material id"));
          const double      youngs_modulus = prm.get_double("Young's modulus");
          const double      poisson_ratio  = prm.get_double("Poisson's ratio");
          const std::string youngs_modulus_text = prm.get("Young's modulus");
          const std::string poisson_ratio_text  = prm.get("Poisson's ratio");

          AssertThrow(materials.count(id) == 0,
                      dealii::ExcMessage(
                        "Material id " + std::to_string(id) +
                        " is given twice in " + name + " " +
                        io::parameter_location(sub_path, "Material id") + "."));
          AssertThrow(
            youngs_modulus > 0,
            dealii::ExcMessage(
              "Young's modulus must be > 0, got " + youngs_modulus_text + " " +
              io::parameter_location(sub_path, "Young's modulus") + "."));
          // stiffness entries are E h^(dim-2), displacements load / E and
          // the dual's operator E^-1 times the gaps: outside this range
          // they leave the range of doubles (1e+-308) for ordinary loads,
          // in any consistent unit system (a gel of 1e3 Pa ... diamond of
          // 1.2e12 Pa, or 1e-3 ... 1.2e6 in MPa)
          AssertThrow(youngs_modulus >= min_youngs_modulus &&
                        youngs_modulus <= max_youngs_modulus,
                      dealii::ExcMessage(
                        "Young's modulus " + youngs_modulus_text + " " +
                        io::parameter_location(sub_path, "Young's modulus") +
                        " is outside the range [1e-20, 1e20] in which "
                        "dualcontact's stiffness and dual operators stay "
                        "within the range of doubles: use a consistent unit "
                        "system that brings it into the range (e.g. MPa, "
                        "mm and N instead of Pa, m and N)."));
          AssertThrow(poisson_ratio > -1. && poisson_ratio < 0.5,
                      dealii::ExcMessage(
                        "Poisson's ratio must lie in (-1, 0.5), got " +
                        poisson_ratio_text + " " +
                        io::parameter_location(sub_path, "Poisson's ratio") +
                        "."));
          materials.emplace(id,
                            fem::IsotropicMaterial(youngs_modulus,
                                                   poisson_ratio,
                                                   name + ", material id " +
                                                     std::to_string(id)));
        });

      dirichlet.clear();
      dirichlet_paths_.clear();
      if (layout.n_dirichlet == 0)
        check_unused_subsection(prm,
                                "Dirichlet 1",
                                "Number of Dirichlet conditions",
                                path,
                                {{"Boundary id", "0"},
                                 {"Components", all_components(dim)},
                                 {"Displacement", io::zero_expressions(dim)}});
      io::for_each_numbered_subsection(
        prm,
        "Dirichlet",
        layout.n_dirichlet,
        path,
        [&](unsigned int, const std::string &sub_path)
        {
          fem::DirichletCondition<dim> condition;
          condition.boundary_id = prm.get_integer("Boundary id");
          std::vector<bool> mask(dim, false);
          for (const auto &component :
               dealii::Utilities::split_string_list(prm.get("Components")))
            mask[component[0] - 'x'] = true;
          AssertThrow(std::find(mask.begin(), mask.end(), true) != mask.end(),
                      dealii::ExcMessage(
                        "No displacement component is selected " +
                        io::parameter_location(sub_path, "Components") + "."));
          condition.components = dealii::ComponentMask(mask);
          condition.values =
            io::parse_function<dim>(prm.get("Displacement"),
                                    dim,
                                    io::parameter_location(sub_path,
                                                           "Displacement"));
          dirichlet.push_back(condition);
          dirichlet_paths_.push_back(sub_path);
        });

      tractions.clear();
      traction_paths_.clear();
      if (layout.n_tractions == 0)
        check_unused_subsection(prm,
                                "Traction 1",
                                "Number of traction conditions",
                                path,
                                {{"Boundary id", "1"},
                                 {"Traction", io::zero_expressions(dim)}});
      io::for_each_numbered_subsection(
        prm,
        "Traction",
        layout.n_tractions,
        path,
        [&](unsigned int, const std::string &sub_path)
        {
          fem::TractionCondition<dim> condition;
          condition.boundary_id = prm.get_integer("Boundary id");
          condition.traction =
            io::parse_function<dim>(prm.get("Traction"),
                                    dim,
                                    io::parameter_location(sub_path,
                                                           "Traction"));
          tractions.push_back(condition);
          traction_paths_.push_back(sub_path);
        });

      const std::string body_force_text = prm.get("Body force");
      body_force =
        io::parse_function<dim>(body_force_text,
                                dim,
                                io::parameter_location(path, "Body force"));
      has_body_force =
        (dealii::Utilities::trim(body_force_text) != io::zero_expressions(dim));
    }


    template <int dim>
    void
    BodyParameters<dim>::check_mesh(
      const dealii::Triangulation<dim> &triangulation,
      const bool                        in_contact) const
    {
      const std::vector<dealii::types::boundary_id> ids =
        triangulation.get_boundary_ids();
      const auto check_id =
        [&](const dealii::types::boundary_id id, const std::string &sub_path)
      {
        AssertThrow(std::find(ids.begin(), ids.end(), id) != ids.end(),
                    dealii::ExcMessage(
                      "The mesh of " + name + " has no boundary id " +
                      std::to_string(id) +
                      " (its boundary ids: " + io::join_numbers(ids) + ") " +
                      io::parameter_location(sub_path, "Boundary id") + "."));
      };
      for (unsigned int n = 0; n < dirichlet.size(); ++n)
        check_id(dirichlet[n].boundary_id, dirichlet_paths_[n]);
      for (unsigned int n = 0; n < tractions.size(); ++n)
        check_id(tractions[n].boundary_id, traction_paths_[n]);

      std::set<dealii::types::material_id> missing;
      for (const auto &cell : triangulation.active_cell_iterators())
        if (materials.count(cell->material_id()) == 0)
          missing.insert(cell->material_id());
      if (!missing.empty())
      {
        AssertThrow(false,
                    dealii::ExcMessage(
                      "Cells of " + name + " have material id(s) " +
                      io::join_numbers(std::vector<unsigned int>(
                        missing.begin(), missing.end())) +
                      ", for which no material is given (`set Material "
                      "id' in the subsections `" +
                      path_ +
                      "/Material N'; `set Number of materials' in "
                      "`subsection " +
                      path_ + "')."));
      }

      AssertThrow(!dirichlet.empty() || in_contact,
                  dealii::ExcMessage(
                    name +
                    " has no Dirichlet condition, so it could move "
                    "freely and its stiffness matrix is singular; a "
                    "floating body must be held by contact: make it the "
                    "slave or master of a `Contact pair N' " +
                    io::parameter_location(path_,
                                           "Number of Dirichlet conditions") +
                    "."));
    }


    template class BodyParameters<2>;
    template class BodyParameters<3>;
  } // namespace driver
} // namespace dualcontact
