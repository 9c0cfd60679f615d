#pragma once

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/numerics/rtree.h>

#include <fem/elastic_body.h>

#include <string>
#include <utility>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * The contact boundary of a master body (the faces with one boundary
     * id) and the search for the face closest to a point.
     *
     * The faces' bounding boxes are kept in an R-tree (deal.II's
     * pack_rtree(), boost.geometry underneath).  closest_face() projects x
     * on the face of the nearest box, whose distance R bounds the answer,
     * then on every face whose box meets the cube of half-width R around
     * x.  A face lies inside its box (a bilinear face is a convex
     * combination of its vertices), so no face left out can be closer: the
     * answer is the one of a loop over all faces, ties included (the lowest
     * face index among equally distant faces), at the cost of a few faces
     * per point instead of all of them.  The loop over all faces made the
     * search quadratic: 61 s for 25,921 slave nodes against 26,244 master
     * faces (two stacked boxes), 45 % of the whole run.
     *
     * The boxes are also what a distributed search exchanges (issue 17):
     * a process needs the master faces whose boxes come within the search
     * distance of its slave nodes only.
     */
    template <int dim>
    class MasterSurface
    {
    public:
      /** A face of the master body's contact boundary. */
      struct Face
      {
        typename dealii::DoFHandler<dim>::active_cell_iterator cell;
        unsigned int                                           face_no;
        std::vector<dealii::Point<dim>>                        vertices;
        dealii::Point<dim>                                     cell_center;
      };

      /** The closest face to a point, the closest point on it and the
       * master cell's outward unit normal there. */
      struct Projection
      {
        unsigned int           face = 0;
        double                 distance_square;
        dealii::Point<dim>     point;
        dealii::Tensor<1, dim> outward_normal;
      };

      /**
       * The faces of @p master with boundary id @p boundary_id (on a
       * distributed mesh those of the owned cells: a process may have
       * none).  Throws, naming @p pair_name, if there are none (on a
       * distributed mesh: on no process; collective there).
       */
      MasterSurface(const fem::ElasticBody<dim>     &master,
                    const dealii::types::boundary_id boundary_id,
                    const std::string               &pair_name);

      unsigned int
      n_faces() const;

      const Face &
      face(const unsigned int f) const;

      /** The face closest to @p x, as a loop over all faces would find it
       * (requires at least one face). */
      Projection
      closest_face(const dealii::Point<dim> &x) const;

      /** The faces whose bounding boxes meet @p box (the mortar's faces
       * near a slave face), in increasing order. */
      std::vector<unsigned int>
      faces_in_box(const dealii::BoundingBox<dim> &box) const;

      /**
       * Closest point to @p x on a boundary face given by its vertices
       * (a segment in 2D, a triangle or a bilinear quadrilateral in 3D:
       * FaceGeometry::project()) and the unit
       * normal there (orientation not fixed).  Returns the squared
       * distance.
       */
      static double
      project_on_face(const std::vector<dealii::Point<dim>> &vertices,
                      const dealii::Point<dim>              &x,
                      dealii::Point<dim>                    &closest,
                      dealii::Tensor<1, dim>                &normal);

    private:
      using Leaf = std::pair<dealii::BoundingBox<dim>, unsigned int>;

      std::vector<Face>   faces_;
      dealii::RTree<Leaf> tree_;
      /** (1e-10 times the largest face box's diagonal)^2 [m^2]: distances
       * closer than this to the best one are visited too. */
      double margin_square_ = 0;
    };
  } // namespace contact
} // namespace dualcontact
