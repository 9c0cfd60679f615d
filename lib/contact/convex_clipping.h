#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>

#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * The overlap of two convex regions of a line (plane_dim = 1: intervals
     * given by their two end points) or of a plane (plane_dim = 2: convex
     * polygons given by their vertices in cyclic order, either
     * orientation), and a quadrature on the overlap: what the mortar
     * integrals need after the slave and master faces have been projected
     * onto the slave face's line or plane (MortarCoupling).
     *
     * Polygons are clipped by Sutherland and Hodgman's algorithm (the
     * subject clipped by each edge of the clip polygon in turn), which is
     * exact for convex clip polygons; the overlap of two convex polygons is
     * convex, so it is integrated on the triangles of a fan from its
     * centroid.  Points within @p tolerance of an edge count as inside, so
     * that faces sharing an edge (the common case of matching meshes) give
     * the shared region once and not a sliver.
     */
    class ConvexClipping
    {
    public:
      /**
       * The overlap of the intervals or polygons @p subject and @p clip
       * (empty, or fewer than plane_dim + 1 points, when they do not
       * overlap); @p tolerance [m] is the distance within which a point
       * counts as on an edge.
       */
      template <int plane_dim>
      static std::vector<dealii::Point<plane_dim>>
      overlap(const std::vector<dealii::Point<plane_dim>> &subject,
              const std::vector<dealii::Point<plane_dim>> &clip,
              const double                                 tolerance);

      /**
       * A Gauss rule on the convex region @p region (as overlap() returns
       * it) in real coordinates, weights the measure (length, area): on an
       * interval QGauss with @p n_points, on a polygon QGaussSimplex with
       * @p n_points per direction on each triangle of the fan.
       */
      template <int plane_dim>
      static dealii::Quadrature<plane_dim>
      quadrature(const std::vector<dealii::Point<plane_dim>> &region,
                 const unsigned int                           n_points);

      /** Twice the signed area of a polygon (positive counterclockwise). */
      static double
      twice_signed_area(const std::vector<dealii::Point<2>> &polygon);
    };


    template <>
    std::vector<dealii::Point<1>>
    ConvexClipping::overlap<1>(const std::vector<dealii::Point<1>> &,
                               const std::vector<dealii::Point<1>> &,
                               const double);
    template <>
    std::vector<dealii::Point<2>>
    ConvexClipping::overlap<2>(const std::vector<dealii::Point<2>> &,
                               const std::vector<dealii::Point<2>> &,
                               const double);
    template <>
    dealii::Quadrature<1>
    ConvexClipping::quadrature<1>(const std::vector<dealii::Point<1>> &,
                                  const unsigned int);
    template <>
    dealii::Quadrature<2>
    ConvexClipping::quadrature<2>(const std::vector<dealii::Point<2>> &,
                                  const unsigned int);
  } // namespace contact
} // namespace dualcontact
