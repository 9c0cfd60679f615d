#pragma once

#include <deal.II/base/parameter_handler.h>

#include <contact/rigid_obstacle.h>

#include <memory>
#include <string>

namespace dualcontact
{
  namespace driver
  {
    /**
     * One rigid obstacle of a scene (subsection `Obstacle N'): a plane
     * (contact::PlaneObstacle) or the region below the graph of a height
     * function (contact::GraphObstacle).  Obstacles do not move; contact
     * pairs refer to them as `Master = obstacle N'.
     *
     * The obstacle is built while the parameters are read, so that a bad
     * value (zero normal, an expression that does not parse) is reported
     * before anything is computed.
     */
    template <int dim>
    class ObstacleParameters
    {
    public:
      /** Declare the entries of `Obstacle N' in the current subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /**
       * Read the current subsection, whose path is @p path ("Obstacle 1"),
       * check the values and build the obstacle.
       */
      void
      parse_parameters(dealii::ParameterHandler &prm, const std::string &path);

      std::string                                        name;
      std::shared_ptr<const contact::RigidObstacle<dim>> obstacle;
    };
  } // namespace driver
} // namespace dualcontact
