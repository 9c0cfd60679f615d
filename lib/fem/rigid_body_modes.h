#pragma once

#include <deal.II/lac/vector.h>

#include <fem/elastic_body.h>

#include <vector>

namespace dualcontact
{
  namespace fem
  {
    /**
     * The kernel of the stiffness matrix of a body without Dirichlet
     * conditions ("floating"): the rigid-body motions, dim translations and
     * dim (dim - 1) / 2 rotations about the body's centroid, evaluated at the
     * dof support points and orthonormalized (so that G = R'B' is well
     * scaled whatever the body's size).
     *
     * Dofs constrained by hanging nodes are decoupled in the condensed K, so
     * the modes are zero there: the kernel of the condensed matrix.
     *
     * Also chooses the "fixing dofs" of a generalized inverse: n_modes dofs
     * such that R restricted to them is nonsingular (all components of a node
     * A, then dim - 1 of a node B far from A, then in 3D one of a node C far
     * from the line AB).  Deleting them from K leaves a nonsingular matrix
     * K_rr, and diag(K_rr^{-1}, 0) is a generalized inverse of K.
     */
    template <int dim>
    class RigidBodyModes
    {
    public:
      explicit RigidBodyModes(const ElasticBody<dim> &body);

      /** dim (dim + 1) / 2. */
      static constexpr unsigned int n_modes = dim * (dim + 1) / 2;

      /** Orthonormal basis of the rigid-body motions (columns of R). */
      const std::vector<dealii::Vector<double>> &
      modes() const;

      /** The n_modes fixing dofs (see the class documentation). */
      const std::vector<dealii::types::global_dof_index> &
      fixing_dofs() const;

    private:
      std::vector<dealii::Vector<double>>          modes_;
      std::vector<dealii::types::global_dof_index> fixing_dofs_;
    };
  } // namespace fem
} // namespace dualcontact
