#pragma once

#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <contact/friction_law.h>
#include <contact/rigid_obstacle.h>

#include <limits>
#include <memory>
#include <string>

namespace dualcontact
{
  namespace contact
  {
    /**
     * One contact pair: the slave surface (boundary id of a body) whose
     * nodes carry the contact constraints, and the master, either a rigid
     * obstacle or the surface (boundary id) of another body.  Non-matching
     * meshes are allowed: each slave node is projected onto the closest
     * master face.
     */
    template <int dim>
    struct ContactPair
    {
      std::string                name;
      unsigned int               slave_body     = 0;
      dealii::types::boundary_id slave_boundary = 0;

      /** Set for body-obstacle pairs; then master_body is ignored. */
      std::shared_ptr<const RigidObstacle<dim>> obstacle;
      unsigned int                              master_body     = 0;
      dealii::types::boundary_id                master_boundary = 0;

      /**
       * Slave nodes farther than this from the master [m] are not contact
       * nodes: in small displacements they cannot touch.
       */
      double search_distance = std::numeric_limits<double>::max();

      /**
       * 3D: the first tangent of every node is the projection of this
       * direction onto the node's tangent plane (orthotropic friction
       * refers to it); when it is (almost) normal there, the coordinate axis
       * least aligned with the normal is used.  Ignored in 2D.
       */
      dealii::Tensor<1, dim> first_tangent_direction;

      FrictionLaw friction;
    };
  } // namespace contact
} // namespace dualcontact
