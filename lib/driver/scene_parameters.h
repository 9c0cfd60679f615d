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
     * entries rejected.
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
    };
  } // namespace driver
} // namespace dualcontact
