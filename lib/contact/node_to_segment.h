#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <contact/contact_discretization.h>
#include <contact/contact_pair.h>
#include <contact/master_surface.h>
#include <contact/row_entries.h>
#include <fem/elastic_body.h>

#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * Node-to-segment placement of one pair's slave nodes (`Discretization
     * = node to segment'): each node at its closest point of the master
     * (an obstacle's projection, or the closest master face through
     * MasterSurface), its normal minus the master's outward normal there,
     * and the master body's shape functions at that point as its row's
     * master entries.  On a distributed master body all nodes are placed
     * at construction (collective): every process projects on its own
     * faces, the closest over the processes wins (MPI_MINLOC; equal
     * distances: the lowest process), and the winner sends the placement
     * to all (one gather of the placements, not of the faces).
     */
    template <int dim>
    class NodeToSegment
    {
    public:
      /**
       * The placement of the slave nodes at @p positions of @p pair, the
       * master body (if any) of @p bodies with its surface @p surface
       * (null for an obstacle).  Collective on a distributed master.
       */
      NodeToSegment(const ContactPair<dim>                           &pair,
                    const std::vector<const fem::ElasticBody<dim> *> &bodies,
                    const MasterSurface<dim>                         *surface,
                    const std::vector<dealii::Point<dim>> &positions);

      /**
       * Places node @p i (of the constructor's positions; @p node's
       * position set): its master_point, normal and @p master's entries.
       * False when the master is farther than the search distance.
       */
      bool
      place(const unsigned int i,
            ContactNode<dim>  &node,
            MasterEntries     &master) const;

    private:
      /** Where a slave node lies on a distributed master body. */
      struct Placement
      {
        bool                   found = false;
        dealii::Point<dim>     master_point;
        dealii::Tensor<1, dim> normal;
        MasterEntries          entries;
      };

      /** Places @p node on the master body's faces (this process'). */
      bool
      place_on_master_body(ContactNode<dim> &node,
                           MasterEntries    &master_entries) const;
      /** Every node of @p positions placed over the processes' faces. */
      void
      place_on_distributed_master(
        const std::vector<dealii::Point<dim>> &positions);

      const ContactPair<dim>      &pair_;
      const fem::ElasticBody<dim> *master_;
      const MasterSurface<dim>    *surface_;
      /** A distributed master: the placements of all nodes. */
      std::vector<Placement> placements_;
    };
  } // namespace contact
} // namespace dualcontact
