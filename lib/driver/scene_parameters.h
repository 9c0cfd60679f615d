#pragma once

#include <deal.II/base/parameter_handler.h>

#include <driver/scene_layout.h>
#include <io/parameter_file.h>

#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace driver
  {
    /**
     * The whole parameter file.  Top level: `Dimension', `Number of bodies';
     * subsections `Discretization', `Output', `Stiffness solver'
     * (fem::StiffnessSolver), `QP solver' and `QP solver/SMALSE-M' (lib/qp),
     * `Coulomb' (contact::CoulombParameters), `Body 1', `Body 2', ...
     * (BodyParameters), `Obstacle 1', ... (ObstacleParameters) and `Contact
     * pair 1', ... (ContactPairParameters).
     *
     * Because the number of bodies (and of materials and boundary
     * conditions per body) is itself a parameter, the file is read in three
     * passes: the first reads `Dimension' and `Number of bodies' (ignoring
     * everything else), the second the `Number of ...' entries of every
     * body, the third everything, with every entry declared and unknown
     * entries rejected.  After the third pass every numbered
     * subsection up to a count the file sets must be written in it.
     */
    class SceneParameters
    {
    public:
      /** Declare every parameter of a scene shaped like @p layout. */
      static void
      declare_parameters(dealii::ParameterHandler &prm,
                         const SceneLayout        &layout);

      /**
       * Read @p file_name in the three passes; the result is complete.
       * @p overrides (the command line's `--set') are applied after the
       * file in every pass, so that they may also change the layout
       * (`Number of bodies', ...); in the last pass an override of an
       * entry the scene does not have is an error, as an unknown entry
       * of the file is.
       */
      static std::unique_ptr<dealii::ParameterHandler>
      read(const std::string                        &file_name,
           SceneLayout                              &layout,
           const std::vector<io::ParameterOverride> &overrides = {});

    private:
      static void
      declare_top_level_entries(dealii::ParameterHandler &prm);

      /**
       * Throw unless @p file_name writes every numbered subsection (`Body
       * N', `Body N/Material M', `Dirichlet M', `Traction M', `Obstacle N',
       * `Contact pair N') up to its count in @p layout, for every count the
       * file sets (`set Number of ...'; a count left at its default asks for
       * nothing, so that a body of the default material needs no `Material
       * 1').  "Written" is the subsection's header in the file, so that a
       * subsection whose entries all keep their defaults is still one the
       * user meant, while a count one too high no longer adds a default
       * body, material or condition silently.
       */
      static void
      check_numbered_subsections_written(const std::string &file_name,
                                         const SceneLayout &layout);
    };
  } // namespace driver
} // namespace dualcontact
