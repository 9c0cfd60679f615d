#include <deal.II/base/patterns.h>

#include <driver/body_parameters.h>
#include <driver/scene_parameters.h>
#include <fem/stiffness_solver.h>
#include <io/parameter_file.h>

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
      prm.leave_subsection();

      prm.enter_subsection("Output");
      prm.declare_entry("Output folder",
                        "output",
                        dealii::Patterns::Anything(),
                        "Folder for the results, relative to the working "
                        "directory; created if missing. It receives "
                        "solution.pvd (open this in ParaView), solution.pvtu, "
                        "body_N.vtu, results.txt, statistics.json and "
                        "used_parameters.prm.");
      prm.declare_entry("Write VTU",
                        "true",
                        dealii::Patterns::Bool(),
                        "Whether to write the VTU/PVTU/PVD visualization "
                        "files (the other files are always written).");
      prm.leave_subsection();

      fem::StiffnessSolver::declare_parameters(prm);

      if (layout.dimension == 2)
        declare_bodies<2>(prm, layout);
      else
        declare_bodies<3>(prm, layout);
    }


    std::unique_ptr<dealii::ParameterHandler>
    SceneParameters::read(const std::string &file_name, SceneLayout &layout)
    {
      // pass 1: dimension and number of bodies
      {
        dealii::ParameterHandler prm;
        declare_top_level_entries(prm);
        io::parse_parameter_file(prm, file_name, true);
        layout.dimension = prm.get_integer("Dimension");
        layout.bodies.assign(prm.get_integer("Number of bodies"), BodyLayout());
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
      return prm;
    }
  } // namespace driver
} // namespace dualcontact
