#include <deal.II/base/quadrature_lib.h>

#include <contact/convex_clipping.h>

#include <algorithm>
#include <cmath>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    namespace
    {
      /** (b - a) x (p - a): positive when p lies left of a -> b. */
      double
      cross(const Point<2> &a, const Point<2> &b, const Point<2> &p)
      {
        return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
      }


      /** @p polygon counterclockwise (reversed if it is not). */
      std::vector<Point<2>>
      counterclockwise(std::vector<Point<2>> polygon)
      {
        if (ConvexClipping::twice_signed_area(polygon) < 0)
          std::reverse(polygon.begin(), polygon.end());
        return polygon;
      }


      /** The part of @p subject left of the directed line a -> b (within
       * @p tolerance of it counts as left). */
      std::vector<Point<2>>
      clip_by_edge(const std::vector<Point<2>> &subject,
                   const Point<2>              &a,
                   const Point<2>              &b,
                   const double                 tolerance)
      {
        std::vector<Point<2>> result;
        const double          length = a.distance(b);
        // signed distance of p from the line, positive inside; within the
        // tolerance a point counts as inside, but the crossings are those of
        // the line itself, so that the tolerance never inflates the area
        const auto side = [&](const Point<2> &p)
        { return cross(a, b, p) / length; };
        for (unsigned int i = 0; i < subject.size(); ++i)
        {
          const Point<2> &p  = subject[i];
          const Point<2> &q  = subject[(i + 1) % subject.size()];
          const double    sp = side(p), sq = side(q);
          const bool      p_in = sp >= -tolerance, q_in = sq >= -tolerance;
          if (p_in)
            result.push_back(p);
          if (p_in != q_in)
            result.push_back(p + std::clamp(sp / (sp - sq), 0., 1.) * (q - p));
        }
        return result;
      }
    } // namespace


    double
    ConvexClipping::twice_signed_area(const std::vector<Point<2>> &polygon)
    {
      double area = 0;
      for (unsigned int i = 0; i < polygon.size(); ++i)
      {
        const Point<2> &p = polygon[i];
        const Point<2> &q = polygon[(i + 1) % polygon.size()];
        area += p[0] * q[1] - q[0] * p[1];
      }
      return area;
    }


    template <>
    std::vector<Point<1>>
    ConvexClipping::overlap<1>(const std::vector<Point<1>> &subject,
                               const std::vector<Point<1>> &clip,
                               const double                 tolerance)
    {
      const double lower = std::max(std::min(subject[0][0], subject[1][0]),
                                    std::min(clip[0][0], clip[1][0]));
      const double upper = std::min(std::max(subject[0][0], subject[1][0]),
                                    std::max(clip[0][0], clip[1][0]));
      if (upper - lower <= tolerance)
        return {};
      return {Point<1>(lower), Point<1>(upper)};
    }


    template <>
    std::vector<Point<2>>
    ConvexClipping::overlap<2>(const std::vector<Point<2>> &subject,
                               const std::vector<Point<2>> &clip,
                               const double                 tolerance)
    {
      std::vector<Point<2>>       result = counterclockwise(subject);
      const std::vector<Point<2>> edges  = counterclockwise(clip);
      for (unsigned int i = 0; i < edges.size() && result.size() > 2; ++i)
        result = clip_by_edge(result,
                              edges[i],
                              edges[(i + 1) % edges.size()],
                              tolerance);
      // slivers along a shared edge: no area to integrate
      if (result.size() < 3 ||
          twice_signed_area(result) <=
            2 * tolerance * std::sqrt(std::abs(twice_signed_area(edges))))
        return {};
      return result;
    }


    template <>
    Quadrature<1>
    ConvexClipping::quadrature<1>(const std::vector<Point<1>> &region,
                                  const unsigned int           n_points)
    {
      const QGauss<1>       rule(n_points);
      std::vector<Point<1>> points;
      std::vector<double>   weights;
      const double          length = region[1][0] - region[0][0];
      for (unsigned int q = 0; q < rule.size(); ++q)
      {
        points.emplace_back(region[0][0] + length * rule.point(q)[0]);
        weights.push_back(std::abs(length) * rule.weight(q));
      }
      return Quadrature<1>(points, weights);
    }


    template <>
    Quadrature<2>
    ConvexClipping::quadrature<2>(const std::vector<Point<2>> &region,
                                  const unsigned int           n_points)
    {
      const QGaussSimplex<2> rule(n_points);
      Point<2>               centroid;
      for (const Point<2> &p : region)
        centroid += p / static_cast<double>(region.size());
      std::vector<Point<2>> points;
      std::vector<double>   weights;
      for (unsigned int i = 0; i < region.size(); ++i)
      {
        // the triangle (centroid, p, q): x = c + s (p - c) + r (q - c)
        const Point<2>    &p = region[i];
        const Point<2>    &q = region[(i + 1) % region.size()];
        const Tensor<1, 2> a = p - centroid, b = q - centroid;
        const double       twice_area = std::abs(a[0] * b[1] - a[1] * b[0]);
        for (unsigned int k = 0; k < rule.size(); ++k)
        {
          points.push_back(centroid + rule.point(k)[0] * a +
                           rule.point(k)[1] * b);
          // the reference triangle has area 1/2
          weights.push_back(rule.weight(k) * twice_area);
        }
      }
      return Quadrature<2>(points, weights);
    }
  } // namespace contact
} // namespace dualcontact
