#pragma once

#include <deal.II/lac/vector.h>

#include <fem/elastic_body.h>

#include <string>
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

      /**
       * The modes of a subdomain: the dofs @p dofs of a body (indices into
       * @p support_points and @p components, the body's dof support points
       * and vector components, DoFTools::map_dofs_to_support_points), all
       * floating, as for a stiffness matrix assembled from a set of cells
       * without Dirichlet conditions: all dim (dim + 1) / 2 modes, about the
       * subdomain's centroid, in the local numbering of @p dofs (mode(i)
       * belongs to dofs[i], fixing_dofs() are local indices).  @p name is
       * used in messages.
       */
      RigidBodyModes(const std::vector<dealii::Point<dim>> &support_points,
                     const std::vector<unsigned int>       &components,
                     const std::vector<dealii::types::global_dof_index> &dofs,
                     const std::string                                  &name);

      /**
       * The number of rigid-body motions that Dirichlet conditions at the
       * dofs with support points @p points and vector components
       * @p components do not hold (the kernel of M'M as in the
       * constructors, M the motions at these dofs): a body on a
       * distributed mesh, whose supported dofs are gathered from the
       * processes, floats when this is positive.
       */
      static unsigned int
      n_free_motions(const std::vector<dealii::Point<dim>> &points,
                     const std::vector<unsigned int>       &components);

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
      /**
       * The work of both constructors on the local dofs: @p points and
       * @p component per local dof, @p constraints (null: all floating)
       * indexed through @p dofs.
       */
      void
      build(const std::vector<dealii::Point<dim>>              &points,
            const std::vector<unsigned int>                    &component,
            const std::vector<dealii::types::global_dof_index> &dofs,
            const dealii::AffineConstraints<double>            *constraints,
            const std::string                                  &name);

      std::vector<dealii::Vector<double>>          modes_;
      std::vector<dealii::types::global_dof_index> fixing_dofs_;
    };
  } // namespace fem
} // namespace dualcontact
