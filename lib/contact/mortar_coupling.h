#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>
#include <deal.II/lac/affine_constraints.h>

#include <contact/contact_discretization.h>
#include <contact/contact_pair.h>
#include <contact/face_geometry.h>
#include <contact/master_surface.h>
#include <contact/row_entries.h>
#include <fem/elastic_body.h>

#include <array>
#include <map>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * The dual mortar coupling of one contact pair (small displacements,
     * reference configuration; design.md, "Dual mortar"): per slave node j
     * the integrals of its dual basis function psi_j (DualBasis) over the
     * slave surface,
     *   D_j    = int psi_j phi_j ds = int phi_j ds          (the weight),
     *   M_jl   = int psi_j (phi_l^master o projection) ds,
     *   S_j    = sum_l M_jl = int_covered psi_j ds,
     *   G_j    = sum_l M_jl x_l - S_j x_j                   (body master),
     *   g~_j   = int psi_j g ds, g the obstacle's signed distance (obstacle),
     * from which ContactDiscretization builds node j's rows
     * n_j . (u_j - sum_l (M_jl / S_j) u_l) <= n_j . G_j / S_j, i.e. the
     * mortar row divided by S_j, so that the multiplier stays the nodal
     * force of node-to-segment and everything downstream is unchanged.
     *
     * Integration (segment-to-segment, Puso and Laursen's auxiliary plane):
     * each slave face and the master faces near it are projected along the
     * slave face's normal onto the slave face's line (2D) or plane (3D),
     * clipped (ConvexClipping), and the overlap integrated by Gauss rules;
     * each quadrature point is carried back to both faces along that normal
     * (FaceGeometry::intersect_line()).  For flat faces this is exact, and
     * sum_l M_jl = D_j wherever the slave face is covered, so a rigid
     * translation leaves every row at zero and a uniform traction is
     * transferred exactly: the contact patch test passes to round-off.
     *
     * Master faces taken: those whose boxes meet the slave face's box
     * widened by min(search distance, d + h) (d the distance from the
     * face's centre to the master surface, h its diameter) and whose outward
     * normal opposes the slave face's.  Partly covered slave nodes (at the
     * edge of the master) are kept with S_j < D_j: their row is still a
     * weighted mean of master displacements (coefficients summing to one),
     * consistent for translations; ContactDiscretization drops the nodes
     * whose coverage S_j / D_j is below `Mortar coverage', whose rows would
     * divide by a small or negative integral of psi_j (psi_j is negative
     * near the other vertices).
     *
     * Hanging slave nodes (3D: the midpoint h of a coarse face's edge next
     * to refined faces, u_h = sum_j c_hj u_j): the active slave faces are
     * integrated as they are, h a vertex like any other, and then h's row
     * is condensed into its parents' with the constraint's coefficients,
     * row_j += c_hj row_h (D, S, M, G, g~ alike), which is the multiplier
     * constrained as the displacement, lambda_h = sum_j c_hj lambda_j: a
     * uniform pressure stays representable and is transferred exactly.
     * The slave side of row j is then S_j u_j + sum_h c_hj S_h u_h (the
     * terms in Row::slave); the u_h go through the body's constraints
     * with the rest of the row (ContactDiscretization).  Node-to-segment
     * moves the hanging node's weight to the same parents.
     *
     * Limits, checked with messages naming the pair: degree-1 faces only
     * (Q2 faces need Popp's basis transformation: quadratic faces have
     * vertex integrals of zero or negative sign), meshes that are not
     * distributed.
     */
    template <int dim>
    class MortarCoupling
    {
    public:
      /** A master node in node j's row. */
      struct MasterNode
      {
        std::array<dealii::types::global_dof_index, dim> dofs;
        dealii::Point<dim>                               position;
        /** M_jl [m^2; m in 2D]. */
        double value = 0;
      };

      /** A slave node in node j's row: j itself with S_j, and the
       * hanging nodes h condensed into it with c_hj S_h. */
      struct SlaveTerm
      {
        std::array<dealii::types::global_dof_index, dim> dofs;
        /** [m^2; m in 2D] */
        double value = 0;
      };

      /** Slave node j's integrals (after the condensation of the hanging
       * nodes: sums over j and c_hj times the hanging nodes h of j). */
      struct Row
      {
        dealii::Point<dim> position;
        /** The node's dofs, one per component. */
        std::array<dealii::types::global_dof_index, dim> dofs;
        /** D_j = int phi_j ds over the slave faces of the node [m^2]. */
        double support = 0;
        /** S_j = sum_l M_jl (an obstacle: D_j) [m^2]. */
        double covered = 0;
        /** Body master: G_j [m^3]. */
        dealii::Tensor<1, dim> gap_vector;
        /** Obstacle: int psi_j g ds [m^3]. */
        double weighted_gap = 0;
        /** Body master: M_jl by the master node's first-component dof. */
        std::map<dealii::types::global_dof_index, MasterNode> master;
        /** The slave side: S_j at j, c_hj S_h at the hanging nodes h, by
         * the node's first-component dof (they sum to S_j). */
        std::map<dealii::types::global_dof_index, SlaveTerm> slave;
      };

      /**
       * The integrals of @p pair with slave body @p slave and, for a body
       * master, @p master and its surface @p surface (both null for an
       * obstacle).
       */
      MortarCoupling(const ContactPair<dim>      &pair,
                     const fem::ElasticBody<dim> &slave,
                     const fem::ElasticBody<dim> *master,
                     const MasterSurface<dim>    *surface);

      /** The rows by slave node (the node's first-component dof); none
       * for a hanging node (condensed into its parents'). */
      const std::map<dealii::types::global_dof_index, Row> &
      rows() const;

      /**
       * Places the contact node @p node (slave node @p key, its position
       * set; @p weighted_normal int phi n ds) by its row: an obstacle's
       * normal at the node's closest point (exact), a master body's the
       * averaged normal; @p master's entries M_jl / S~_j (they sum to one:
       * a rigid translation leaves the row at zero) and the slave terms of
       * the hanging nodes condensed into it, c_hj S_h / S~_j, the node's
       * own coefficient S_j / S~_j.  False for a node without a row or
       * without enough master under its faces (`Mortar coverage') or, on
       * an obstacle, beyond the search distance.
       */
      bool
      place(const dealii::types::global_dof_index key,
            const dealii::Tensor<1, dim>         &weighted_normal,
            ContactNode<dim>                     &node,
            MasterEntries                        &master) const;

      /** The weighted gap of slave node @p key along its (final) normal
       * @p normal, divided by S~_j as its row [m]. */
      double
      gap(const dealii::types::global_dof_index key,
          const dealii::Tensor<1, dim>         &normal) const;

    private:
      /** Adds the integrals of one slave face against the master body. */
      void
      integrate_on_master(
        const FaceGeometry<dim>                            &face,
        const dealii::Tensor<1, dim>                       &normal,
        const std::vector<dealii::types::global_dof_index> &keys);
      /** Adds the integrals of one slave face against the obstacle. */
      void
      integrate_on_obstacle(
        const FaceGeometry<dim>                            &face,
        const std::vector<dealii::types::global_dof_index> &keys);
      /** Condenses the rows of the slave body's hanging nodes into their
       * parents' (row_j += c_hj row_h) and removes them. */
      void
      condense_hanging_nodes(const dealii::AffineConstraints<double> &hanging);
      /** Throws, naming the pair, where the mortar integrals do not apply. */
      void
      check_applicable(const fem::ElasticBody<dim> &slave) const;

      const ContactPair<dim>                        &pair_;
      const fem::ElasticBody<dim>                   *master_;
      const MasterSurface<dim>                      *surface_;
      std::map<dealii::types::global_dof_index, Row> rows_;
    };
  } // namespace contact
} // namespace dualcontact
