#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <fem/elastic_body.h>

#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * The measure of the contact zone of one pair on its slave surface
     * (length in 2D, area in 3D), with the contact edge located below the
     * node spacing.
     *
     * Counting the nodes in contact resolves the edge only to the node
     * spacing h.  Near the edge of a contact between smooth surfaces the
     * pressure vanishes like the square root of the distance d to the edge
     * (p = C sqrt(d), Hertz's p0 sqrt(1 - r^2 / a^2) being one case), so
     * p^2 is linear in d there.  The level function psi = p^2 is therefore
     * set at the nodes in contact, and at every separated node j next to one
     * (sharing a slave face) it is extrapolated linearly from that contact
     * node c and the neighbour c' of c on the far side (the face neighbour of
     * c whose direction from c is most nearly opposite to j):
     *   psi_j = psi_c + (psi_c - psi_c') |x_j - x_c| / |x_c - x_c'|,
     * the mean over j's contact neighbours, and at most -1e-12 max psi (if
     * the pressure does not fall towards j, the edge is put at j).  Without
     * such a c' (no contact node on the far side within 45 degrees of the
     * line) psi_j = -psi_c, the edge at the midpoint.  Before that, every
     * contact node c next to a separated node is checked against its
     * interior: p^2 extrapolated to x_c from the two contact nodes c'', c'
     * behind it on the line from the separated node through c (each the far
     * neighbour as above).  If that is negative (the mean over c's
     * separated neighbours), the interior puts the edge before c: c is in
     * contact only through the force of the element that straddles the
     * edge, lumped onto it (seen on the Hertz meshes: a node at 1.010 a
     * with 0.039 p0), its p_c^2 is no value of p^2 at x_c, and psi_c is the
     * extrapolated value instead.  Separated nodes away
     * from the contact zone get -max psi.  The contact zone is {psi_h > 0},
     * psi_h the finite element interpolant of the nodal psi on the slave
     * faces (hanging nodes from their parents): faces with psi >= 0 at all
     * their nodes count whole, faces with both signs are integrated with an
     * iterated midpoint rule of `cut_face_subdivisions' points per
     * direction.  On the Hertz meshes the edge found so is within a fraction
     * of a percent of the closed form where the node spacing is a few
     * percent of a (doc/hertz.md).
     */
    template <int dim>
    class ContactExtent
    {
    public:
      /** One slave node of the pair, as the contact solution reports it. */
      struct Node
      {
        /** Its component-0 dof in the slave body's numbering. */
        dealii::types::global_dof_index dof = 0;
        dealii::Point<dim>              position;
        /** Normal contact pressure lambda_N / w [Pa]. */
        double pressure = 0;
        /** Whether the node counts as in contact (its status). */
        bool in_contact = false;
      };

      /**
       * Points per direction of the midpoint rule on faces that the contact
       * edge crosses: the edge is then placed to 1/(2 n) of the face size.
       */
      static constexpr unsigned int cut_face_subdivisions = dim == 2 ? 256 : 32;

      /**
       * Compute the contact zone of the nodes @p nodes, which lie on the
       * faces of @p slave with boundary id @p slave_boundary.  On a
       * distributed mesh @p nodes are the pair's nodes of all processes
       * (the same list everywhere), each process integrates the faces of
       * its owned cells and the measure is their sum (collective over the
       * slave's communicator).
       */
      ContactExtent(const fem::ElasticBody<dim>     &slave,
                    const dealii::types::boundary_id slave_boundary,
                    const std::vector<Node>         &nodes);

      /** Length (2D) [m] or area (3D) [m^2] of the contact zone. */
      double
      measure() const
      {
        return measure_;
      }

      /** The nodal level function psi (positive in contact) [Pa^2]. */
      const std::vector<double> &
      level_function() const
      {
        return psi_;
      }

    private:
      /** psi at the nodes (see the class documentation). */
      void
      compute_level_function(const std::vector<Node> &nodes);

      /**
       * The contact neighbour k of node @p c whose direction from c is most
       * nearly opposite to @p direction (within 45 degrees), or -1.
       */
      int
      far_neighbour(const std::vector<Node>      &nodes,
                    const unsigned int            c,
                    const dealii::Tensor<1, dim> &direction) const;

      /**
       * @p psi extrapolated linearly along the line from node @p inner
       * through node @p outer to @p target.
       */
      static double
      extrapolate(const std::vector<Node>   &nodes,
                  const std::vector<double> &psi,
                  const unsigned int         inner,
                  const unsigned int         outer,
                  const dealii::Point<dim>  &target);

      /** The measure of {psi_h > 0} over the slave faces. */
      void
      integrate_zone(const fem::ElasticBody<dim>     &slave,
                     const dealii::types::boundary_id slave_boundary,
                     const std::vector<Node>         &nodes);

      /** Per node, the other nodes on its slave faces. */
      std::vector<std::vector<unsigned int>> neighbours_;
      std::vector<double>                    psi_;
      double                                 measure_ = 0;
    };
  } // namespace contact
} // namespace dualcontact
