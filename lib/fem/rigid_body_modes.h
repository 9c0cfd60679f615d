#pragma once

#include <deal.II/lac/vector.h>

#include <fem/elastic_body.h>

#include <vector>

namespace dualcontact
{
  namespace fem
  {
    /**
     * The kernel of the (condensed) stiffness matrix of a body: the rigid-body
     * motions (dim translations and dim (dim - 1) / 2 rotations about the
     * body's centroid) that its Dirichlet conditions do not prevent, i.e. the
     * kernel of the motions restricted to the Dirichlet-constrained dofs.  A
     * body without Dirichlet conditions ("floating") has all of them, a body
     * on a roller some, a clamped body none.  Evaluated at the dof support
     * points and orthonormalized, so that G = R'B' is well scaled whatever
     * the body's size.
     *
     * Dofs constrained by hanging nodes are decoupled in the condensed K, so
     * the modes are zero there: the kernel of the condensed matrix.
     *
     * Also chooses the "fixing dofs" of a generalized inverse: n_modes() dofs
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

      /** Number of free rigid-body motions, at most dim (dim + 1) / 2. */
      unsigned int
      n_modes() const;

      /** Orthonormal basis of the rigid-body motions (columns of R). */
      const std::vector<dealii::Vector<double>> &
      modes() const;

      /** The n_modes() fixing dofs (see the class documentation). */
      const std::vector<dealii::types::global_dof_index> &
      fixing_dofs() const;

    private:
      std::vector<dealii::Vector<double>>          modes_;
      std::vector<dealii::types::global_dof_index> fixing_dofs_;
    };
  } // namespace fem
} // namespace dualcontact
