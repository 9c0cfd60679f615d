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

      /** How the slave surface is coupled to the master. */
      enum class Discretization
      {
        /** One slave node, its lumped weight, the master's shape values at
         * its closest point. */
        node_to_segment,
        /** Dual mortar (MortarCoupling): integrals of the slave's dual
         * basis against the master over the projected faces. */
        mortar
      };
      Discretization discretization = Discretization::node_to_segment;

      /**
       * Mortar: slave nodes whose covered integral S_j = int_covered psi_j
       * ds is below this fraction of D_j = int phi_j ds are not contact
       * nodes (no master, or too little of it, under their faces) [-].
       */
      double mortar_coverage = 0.2;
    };
  } // namespace contact
} // namespace dualcontact
