#include <deal.II/base/patterns.h>

#include <contact/contact_solver.h>
#include <contact/working_set.h>
#include <decomposition/decomposition_parameters.h>
#include <driver/body_parameters.h>
#include <driver/contact_pair_parameters.h>
#include <driver/contact_refinement.h>
#include <driver/load_steps.h>
#include <driver/obstacle_parameters.h>
#include <driver/output_parameters.h>
#include <driver/scene_parameters.h>
#include <fem/stiffness_solver.h>
#include <io/parameter_file.h>
#include <primal/primal_parameters.h>
#include <qp/smalse_m.h>
#include <qp/solver_parameters.h>

namespace dualcontact
{
  namespace driver
  {
    namespace
    {
      std::string
      body_subsection(const unsigned int index)
      {
        return "Body " + std::to_string(index + 1);
      }

      template <int dim>
      void
      declare_bodies(dealii::ParameterHandler &prm, const SceneLayout &layout)
      {
        for (unsigned int b = 0; b < layout.bodies.size(); ++b)
        {
          prm.enter_subsection(body_subsection(b));
          BodyParameters<dim>::declare_parameters(prm, layout.bodies[b]);
          prm.leave_subsection();
        }
      }

      template <int dim>
      void
      declare_contact(dealii::ParameterHandler &prm, const SceneLayout &layout)
      {
        for (unsigned int n = 1; n <= layout.n_obstacles; ++n)
        {
          prm.enter_subsection("Obstacle " + std::to_string(n));
          ObstacleParameters<dim>::declare_parameters(prm);
          prm.leave_subsection();
        }
        for (unsigned int n = 1; n <= layout.n_contact_pairs; ++n)
        {
          prm.enter_subsection("Contact pair " + std::to_string(n));
          ContactPairParameters<dim>::declare_parameters(prm);
          prm.leave_subsection();
        }
      }
    } // namespace


    void
    SceneParameters::declare_top_level_entries(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Dimension",
                        "3",
                        dealii::Patterns::Integer(2, 3),
                        "Space dimension: 2 (plane strain; forces and "
                        "energies per metre of thickness) or 3.");
      prm.declare_entry("Number of bodies",
                        "1",
                        dealii::Patterns::Integer(1, 1000),
                        "Number of bodies, each described by a subsection "
                        "`Body 1', `Body 2', ...");
      prm.declare_entry("Number of obstacles",
                        "0",
                        dealii::Patterns::Integer(0, 1000),
                        "Number of rigid obstacles, each described by a "
                        "subsection `Obstacle 1', `Obstacle 2', ...");
      prm.declare_entry("Number of contact pairs",
                        "0",
                        dealii::Patterns::Integer(0, 1000),
                        "Number of contact pairs (body-obstacle or "
                        "body-body), each described by a subsection "
                        "`Contact pair 1', `Contact pair 2', ... Without "
                        "contact pairs every body is solved on its own.");
    }


    void
    SceneParameters::declare_parameters(dealii::ParameterHandler &prm,
                                        const SceneLayout        &layout)
    {
      declare_top_level_entries(prm);

      prm.enter_subsection("Discretization");
      prm.declare_entry("Finite element degree",
                        "1",
                        dealii::Patterns::Integer(1, 2),
                        "Polynomial degree p of the FE_Q(p) displacement "
                        "elements of all bodies (1 or 2); the geometry is "
                        "mapped with the same degree.");
      prm.declare_entry(
        "Curved load mapping degree",
        "4",
        dealii::Patterns::Integer(1, 10),
        "Degree of the mapping (on the manifolds of the generated meshes) "
        "with which tractions are integrated on faces that touch a curved "
        "boundary (their own surface or, in 3D, an edge, e.g. the flat top "
        "of a half ball), so that the load follows the true geometry and not "
        "the chords of the elements; used where it exceeds the finite "
        "element degree.  results.txt compares each traction's resultant "
        "with the one on the exact surface.");
      prm.leave_subsection();

      OutputParameters::declare_parameters(prm);

      fem::StiffnessSolver::declare_parameters(prm);
      contact::DualProblemParameters::declare_parameters(prm);
      contact::WorkingSetParameters::declare_parameters(prm);
      decomposition::DecompositionParameters::declare_parameters(prm);
      qp::SolverParameters::declare_parameters(prm);
      qp::SMALSEMParameters::declare_parameters(prm);
      contact::CoulombParameters::declare_parameters(prm);
      primal::PrimalParameters::declare_parameters(prm);
      ContactRefinement<3>::declare_parameters(prm);
      LoadSteps::declare_parameters(prm);

      if (layout.dimension == 2)
      {
        declare_bodies<2>(prm, layout);
        declare_contact<2>(prm, layout);
      }
      else
      {
        declare_bodies<3>(prm, layout);
        declare_contact<3>(prm, layout);
      }
    }


    void
    SceneParameters::check_numbered_subsections_written(
      const std::string &file_name,
      const SceneLayout &layout)
    {
      const io::ParameterFileOutline outline =
        io::outline_parameter_file(file_name);
      const auto require = [&](const std::string &path,
                               const std::string &name,
                               const unsigned int count,
                               const std::string &count_entry)
      {
        // a count left at its default (one material, no conditions) asks
        // for nothing: a body of the default material needs no `Material 1'
        if (outline.entries.count({path, count_entry}) == 0)
          return;
        for (unsigned int k = 1; k <= count; ++k)
        {
          const std::string subsection =
            io::join_path(path, name + " " + std::to_string(k));
          AssertThrow(outline.subsections.count(subsection) == 1,
                      dealii::ExcMessage(
                        "The input file `" + file_name +
                        "' has no `subsection " + subsection + "', but `" +
                        count_entry + "' is " + std::to_string(count) + " " +
                        io::parameter_location(path, count_entry) +
                        ": write every numbered subsection up to its count "
                        "(`subsection " +
                        name + " " + std::to_string(k) +
                        "' and `end' are enough if all its entries keep "
                        "their defaults), or lower the count."));
        }
      };
      require("", "Body", layout.bodies.size(), "Number of bodies");
      for (unsigned int b = 0; b < layout.bodies.size(); ++b)
      {
        const std::string body = body_subsection(b);
        require(body,
                "Material",
                layout.bodies[b].n_materials,
                "Number of materials");
        require(body,
                "Dirichlet",
                layout.bodies[b].n_dirichlet,
                "Number of Dirichlet conditions");
        require(body,
                "Traction",
                layout.bodies[b].n_tractions,
                "Number of traction conditions");
      }
      require("", "Obstacle", layout.n_obstacles, "Number of obstacles");
      require("",
              "Contact pair",
              layout.n_contact_pairs,
              "Number of contact pairs");
    }


    std::unique_ptr<dealii::ParameterHandler>
    SceneParameters::read(const std::string                        &file_name,
                          SceneLayout                              &layout,
                          const std::vector<io::ParameterOverride> &overrides)
    {
      // pass 1: dimension and number of bodies
      {
        dealii::ParameterHandler prm;
        declare_top_level_entries(prm);
        io::parse_parameter_file(prm, file_name, true);
        io::apply_parameter_overrides(prm, overrides, true);
        layout.dimension = prm.get_integer("Dimension");
        layout.bodies.assign(prm.get_integer("Number of bodies"), BodyLayout());
        layout.n_obstacles     = prm.get_integer("Number of obstacles");
        layout.n_contact_pairs = prm.get_integer("Number of contact pairs");
      }
      // pass 2: the number of materials and conditions of every body
      {
        dealii::ParameterHandler prm;
        declare_top_level_entries(prm);
        for (unsigned int b = 0; b < layout.bodies.size(); ++b)
        {
          prm.enter_subsection(body_subsection(b));
          BodyParameters<3>::declare_layout_entries(prm);
          prm.leave_subsection();
        }
        io::parse_parameter_file(prm, file_name, true);
        io::apply_parameter_overrides(prm, overrides, true);
        for (unsigned int b = 0; b < layout.bodies.size(); ++b)
        {
          prm.enter_subsection(body_subsection(b));
          layout.bodies[b] = BodyParameters<3>::parse_layout(prm);
          prm.leave_subsection();
        }
      }
      // pass 3: everything, nothing undeclared allowed
      auto prm = std::make_unique<dealii::ParameterHandler>();
      declare_parameters(*prm, layout);
      io::parse_parameter_file(*prm, file_name, false);
      check_numbered_subsections_written(file_name, layout);
      io::apply_parameter_overrides(*prm, overrides, false);
      return prm;
    }
  } // namespace driver
} // namespace dualcontact
