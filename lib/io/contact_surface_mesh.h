#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <fem/elastic_body.h>

#include <array>
#include <utility>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    /**
     * The slave surface of one contact pair as cells for the contact-surface
     * file: the faces of the slave body on the slave boundary id (lines in
     * 2D, quadrilaterals in 3D), each over its support points.  A Q2 face is
     * split into 2 lines (2D) or 4 quadrilaterals (3D) between its support
     * points, as the body files subdivide Q2 cells, so every point of the
     * surface is a node of the displacement field.
     *
     * A point is a contact node, a hanging node (3D adaptive meshes: its
     * values are the constraint's combination of its parents', which are
     * contact nodes; it has no multiplier of its own, its weight went to the
     * parents), or neither (a node beyond the pair's search distance: no
     * multiplier, pressure 0).  Only faces with at least one contact-node
     * point are kept: the others carry no contact force.
     *
     * Each cell records the process owning its cell of the slave body
     * (the subdomain id; 0 on one process), so that under MPI each process
     * writes the faces of its own cells.
     */
    template <int dim>
    class ContactSurfaceMesh
    {
    public:
      /** The points of a line (2D), a triangle or a quadrilateral (3D),
       *  VTK's order (counter-clockwise seen from outside the body). */
      using Cell = std::vector<unsigned int>;
      /** (contact node of the pair, coefficient): a point's value is the
       *  sum of coefficient times the nodes' values. */
      using Combination = std::vector<std::pair<unsigned int, double>>;

      ContactSurfaceMesh() = default;

      /**
       * The faces of @p slave on @p boundary_id.  @p node_dofs: per contact
       * node of the pair, in the pair's node order, the dof of its first
       * displacement component.
       */
      ContactSurfaceMesh(
        const fem::ElasticBody<dim>                        &slave,
        const dealii::types::boundary_id                    boundary_id,
        const std::vector<dealii::types::global_dof_index> &node_dofs);

      unsigned int
      n_points() const
      {
        return positions_.size();
      }
      unsigned int
      n_cells() const
      {
        return cells_.size();
      }
      /** Position of a point (reference configuration) [m]. */
      const dealii::Point<dim> &
      position(const unsigned int point) const
      {
        return positions_[point];
      }
      /**
       * The contact nodes a point's values come from: {(i, 1)} for contact
       * node i, the parents for a hanging node, empty for a point that is
       * no contact node and no combination of contact nodes.
       */
      const Combination &
      combination(const unsigned int point) const
      {
        return combinations_[point];
      }
      /** Whether @p point is a contact node itself. */
      bool
      is_contact_node(const unsigned int point) const
      {
        return combinations_[point].size() == 1 &&
               combinations_[point][0].second == 1.;
      }
      const Cell &
      cell(const unsigned int c) const
      {
        return cells_[c];
      }
      /** The process owning cell @p c's cell of the slave body. */
      unsigned int
      owner(const unsigned int c) const
      {
        return owners_[c];
      }

      /**
       * For tests and hand-made surfaces: points, their combinations, cells
       * and owners given directly.
       */
      ContactSurfaceMesh(std::vector<dealii::Point<dim>> positions,
                         std::vector<Combination>        combinations,
                         std::vector<Cell>               cells,
                         std::vector<unsigned int>       owners);

    private:
      /**
       * The faces of a simplex mesh: one line or triangle per face (P1),
       * two lines or four triangles (P2, split at the edge midpoints).
       */
      template <typename CombinationOf>
      void
      add_simplex_faces(const fem::ElasticBody<dim>     &slave,
                        const dealii::types::boundary_id boundary_id,
                        const CombinationOf             &combination_of);

      std::vector<dealii::Point<dim>> positions_;
      std::vector<Combination>        combinations_;
      std::vector<Cell>               cells_;
      std::vector<unsigned int>       owners_;
    };
  } // namespace io
} // namespace dualcontact
