#pragma once

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * The geometry of one boundary face, from its vertices: a segment in
     * 2D, a triangle or a bilinear quadrilateral in 3D.  It is the one place
     * where contact code asks what a face is (its shape functions, its
     * points, normals and area element, the closest point on it and a
     * quadrature on it), so that node-to-segment placement, mortar
     * integration and every cell type (hypercubes and simplices) share one
     * implementation instead of special cases per face type.
     *
     * Reference coordinates are deal.II's for the face's reference cell,
     * with the vertices in deal.II's order:
     *  - segment: s in [0, 1], X = v0 (1 - s) + v1 s;
     *  - triangle: (s, r) with s, r >= 0, s + r <= 1,
     *    X = v0 (1 - s - r) + v1 s + v2 r;
     *  - quadrilateral: (s, r) in [0, 1]^2 (lexicographic vertices),
     *    X = v0 (1-s)(1-r) + v1 s (1-r) + v2 (1-s) r + v3 s r.
     * The geometry is the vertices' (straight / flat / bilinear): a curved
     * Q2 face is approximated by its vertices, as the contact search has
     * always done.
     */
    template <int dim>
    class FaceGeometry
    {
    public:
      static_assert(dim == 2 || dim == 3, "faces of 2D and 3D cells only");

      enum class Shape
      {
        segment,
        triangle,
        quadrilateral
      };

      /** The closest point of the face to a point. */
      struct Projection
      {
        /** Reference coordinates of the closest point. */
        dealii::Point<dim - 1> unit;
        dealii::Point<dim>     point;
        /** Unit normal at the closest point (orientation: the tangents'
         * right-hand rule, see unit_normal()). */
        dealii::Tensor<1, dim> normal;
        double                 distance_square = 0;
      };

      /** Where a straight line meets the face's surface. */
      struct LineIntersection
      {
        /** Reference coordinates of the point met (not clamped: it may lie
         * beyond the face's edges). */
        dealii::Point<dim - 1> unit;
        /** The line parameter t of that point, x + t direction. */
        double t = 0;
        /** False when the line is (nearly) parallel to the face or Newton
         * did not converge. */
        bool found = false;
      };

      /** The face with these vertices (2 in 2D; 3 or 4 in 3D). */
      explicit FaceGeometry(const std::vector<dealii::Point<dim>> &vertices);

      Shape
      shape() const;
      unsigned int
      n_vertices() const;
      const dealii::Point<dim> &
      vertex(const unsigned int v) const;
      const std::vector<dealii::Point<dim>> &
      vertices() const;

      /** The vertex shape function of vertex @p v (linear / bilinear) at
       * the reference point @p unit. */
      double
      shape_value(const unsigned int            v,
                  const dealii::Point<dim - 1> &unit) const;
      /** Its gradient with respect to the reference coordinates. */
      dealii::Tensor<1, dim - 1>
      shape_grad(const unsigned int            v,
                 const dealii::Point<dim - 1> &unit) const;

      /** X(unit). */
      dealii::Point<dim>
      point(const dealii::Point<dim - 1> &unit) const;
      /** dX/ds (and dX/dr in 3D). */
      std::array<dealii::Tensor<1, dim>, dim - 1>
      tangents(const dealii::Point<dim - 1> &unit) const;
      /** The unit normal at @p unit: in 2D (t_y, -t_x) for the tangent t =
       * dX/ds, in 3D dX/ds x dX/dr normalized.  For a face of a cell in
       * deal.II's vertex order this is not always the outward normal:
       * callers orient it (e.g. away from the cell's centre). */
      dealii::Tensor<1, dim>
      unit_normal(const dealii::Point<dim - 1> &unit) const;
      /** The area element |dX/ds| (2D), |dX/ds x dX/dr| (3D) at @p unit:
       * ds = jacobian_determinant d(unit). */
      double
      jacobian_determinant(const dealii::Point<dim - 1> &unit) const;
      /** The face's length (2D) or area (3D). */
      double
      measure() const;
      /** The mean of the vertices. */
      dealii::Point<dim>
      center() const;
      dealii::BoundingBox<dim>
      bounding_box() const;

      /** Whether @p unit lies in the reference cell (within @p tolerance
       * in reference coordinates). */
      bool
      contains_unit_point(const dealii::Point<dim - 1> &unit,
                          const double                  tolerance = 0) const;

      /**
       * The closest point of the face to @p x.  With @p clamp the answer
       * lies on the face (edges and vertices included); without it, the
       * foot of the perpendicular on the face's surface extended beyond
       * its edges (Newton on the same parametrization: exact for segments
       * and triangles, the local minimum near the face for a bilinear
       * quadrilateral), which is what mortar integration needs to carry a
       * point of a clipped polygon back to reference coordinates.
       */
      Projection
      project(const dealii::Point<dim> &x, const bool clamp = true) const;

      /** A reference-face Gauss rule exact for polynomials of degree
       * 2 n - 1 (QGauss on segments and quadrilaterals, QGaussSimplex on
       * triangles); weights on the reference cell (times
       * jacobian_determinant() for ds). */
      dealii::Quadrature<dim - 1>
      reference_quadrature(const unsigned int n_points_1d) const;

      /**
       * The point X(unit) of the face's surface (extended beyond its
       * edges) on the line x + t @p direction: Newton on X(unit) - x - t d
       * = 0, exact in one step for segments and triangles.  This carries a
       * point of the mortar's auxiliary plane back to a slave or master
       * face along the slave face's normal.
       */
      LineIntersection
      intersect_line(const dealii::Point<dim>     &x,
                     const dealii::Tensor<1, dim> &direction) const;

    private:
      Projection
      project_on_segment(const dealii::Point<dim> &x, const bool clamp) const;
      Projection
      project_on_triangle(const dealii::Point<dim> &x, const bool clamp) const;
      Projection
      project_on_quadrilateral(const dealii::Point<dim> &x,
                               const bool                clamp) const;
      /** The reference point of vertex @p v. */
      dealii::Point<dim - 1>
      unit_vertex(const unsigned int v) const;
      /** @p best, or the clamped projection of @p x on the straight edge
       * from vertex @p a to vertex @p b if that is closer. */
      void
      closer_on_edge(const unsigned int        a,
                     const unsigned int        b,
                     const dealii::Point<dim> &x,
                     Projection               &best) const;
      /** The projection record of the reference point @p unit for @p x. */
      Projection
      projection_at(const dealii::Point<dim - 1> &unit,
                    const dealii::Point<dim>     &x) const;

      std::vector<dealii::Point<dim>> vertices_;
      Shape                           shape_;
    };
  } // namespace contact
} // namespace dualcontact
