#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <contact/face_geometry.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    FaceGeometry<dim>::FaceGeometry(const std::vector<Point<dim>> &vertices)
        : vertices_(vertices)
    {
      if constexpr (dim == 2)
      {
        Assert(vertices.size() == 2, ExcDimensionMismatch(vertices.size(), 2));
        shape_ = Shape::segment;
      }
      else
      {
        Assert(vertices.size() == 3 || vertices.size() == 4,
               ExcMessage("A face of a 3D cell has 3 or 4 vertices."));
        shape_ = vertices.size() == 3 ? Shape::triangle : Shape::quadrilateral;
      }
    }


    template <int dim>
    typename FaceGeometry<dim>::Shape
    FaceGeometry<dim>::shape() const
    {
      return shape_;
    }


    template <int dim>
    unsigned int
    FaceGeometry<dim>::n_vertices() const
    {
      return vertices_.size();
    }


    template <int dim>
    const Point<dim> &
    FaceGeometry<dim>::vertex(const unsigned int v) const
    {
      AssertIndexRange(v, vertices_.size());
      return vertices_[v];
    }


    template <int dim>
    const std::vector<Point<dim>> &
    FaceGeometry<dim>::vertices() const
    {
      return vertices_;
    }


    template <int dim>
    double
    FaceGeometry<dim>::shape_value(const unsigned int    v,
                                   const Point<dim - 1> &unit) const
    {
      AssertIndexRange(v, vertices_.size());
      const double s = unit[0];
      if (shape_ == Shape::segment)
        return v == 0 ? 1 - s : s;
      const double r = unit[dim - 2];
      if (shape_ == Shape::triangle)
        return v == 0 ? 1 - s - r : (v == 1 ? s : r);
      const double fs = (v % 2 == 0) ? 1 - s : s;
      const double fr = (v < 2) ? 1 - r : r;
      return fs * fr;
    }


    template <int dim>
    Tensor<1, dim - 1>
    FaceGeometry<dim>::shape_grad(const unsigned int    v,
                                  const Point<dim - 1> &unit) const
    {
      AssertIndexRange(v, vertices_.size());
      Tensor<1, dim - 1> grad;
      if (shape_ == Shape::segment)
      {
        grad[0] = v == 0 ? -1 : 1;
        return grad;
      }
      if (shape_ == Shape::triangle)
      {
        grad[0]       = v == 0 ? -1 : (v == 1 ? 1 : 0);
        grad[dim - 2] = v == 0 ? -1 : (v == 2 ? 1 : 0);
        return grad;
      }
      const double s = unit[0], r = unit[dim - 2];
      const double fs = (v % 2 == 0) ? 1 - s : s, dfs = (v % 2 == 0) ? -1 : 1;
      const double fr = (v < 2) ? 1 - r : r, dfr = (v < 2) ? -1 : 1;
      grad[0]       = dfs * fr;
      grad[dim - 2] = fs * dfr;
      return grad;
    }


    template <int dim>
    Point<dim>
    FaceGeometry<dim>::point(const Point<dim - 1> &unit) const
    {
      const std::vector<Point<dim>> &v = vertices_;
      const double                   s = unit[0];
      // the same expressions as the projections below, so that point(unit)
      // of a projection reproduces its point bit for bit
      if (shape_ == Shape::segment)
        return v[0] + s * (v[1] - v[0]);
      const double r = unit[dim - 2];
      if (shape_ == Shape::triangle)
        return v[0] + s * (v[1] - v[0]) + r * (v[2] - v[0]);
      return Point<dim>(v[0] * ((1 - s) * (1 - r)) + v[1] * (s * (1 - r)) +
                        v[2] * ((1 - s) * r) + v[3] * (s * r));
    }


    template <int dim>
    std::array<Tensor<1, dim>, dim - 1>
    FaceGeometry<dim>::tangents(const Point<dim - 1> &unit) const
    {
      const std::vector<Point<dim>>      &v = vertices_;
      std::array<Tensor<1, dim>, dim - 1> t;
      if (shape_ == Shape::segment)
        t[0] = v[1] - v[0];
      else if (shape_ == Shape::triangle)
      {
        t[0]       = v[1] - v[0];
        t[dim - 2] = v[2] - v[0];
      }
      else
      {
        const double s = unit[0], r = unit[dim - 2];
        t[0]       = (v[1] - v[0]) * (1 - r) + (v[3] - v[2]) * r;
        t[dim - 2] = (v[2] - v[0]) * (1 - s) + (v[3] - v[1]) * s;
      }
      return t;
    }


    template <int dim>
    Tensor<1, dim>
    FaceGeometry<dim>::unit_normal(const Point<dim - 1> &unit) const
    {
      const std::array<Tensor<1, dim>, dim - 1> t = tangents(unit);
      Tensor<1, dim>                            n;
      if constexpr (dim == 2)
      {
        n[0] = t[0][1];
        n[1] = -t[0][0];
      }
      else
        n = cross_product_3d(t[0], t[1]);
      return n / n.norm();
    }


    template <int dim>
    double
    FaceGeometry<dim>::jacobian_determinant(const Point<dim - 1> &unit) const
    {
      const std::array<Tensor<1, dim>, dim - 1> t = tangents(unit);
      if constexpr (dim == 2)
        return t[0].norm();
      else
        return cross_product_3d(t[0], t[1]).norm();
    }


    template <int dim>
    double
    FaceGeometry<dim>::measure() const
    {
      // exact on segments, triangles and parallelograms (constant area
      // element); on a warped quadrilateral a 4 x 4 rule of the smooth
      // area element
      const Quadrature<dim - 1> quadrature = reference_quadrature(4);
      double                    area       = 0;
      for (unsigned int q = 0; q < quadrature.size(); ++q)
        area +=
          quadrature.weight(q) * jacobian_determinant(quadrature.point(q));
      return area;
    }


    template <int dim>
    Point<dim>
    FaceGeometry<dim>::center() const
    {
      Point<dim> c;
      for (const Point<dim> &v : vertices_)
        c += v / static_cast<double>(vertices_.size());
      return c;
    }


    template <int dim>
    BoundingBox<dim>
    FaceGeometry<dim>::bounding_box() const
    {
      return BoundingBox<dim>(vertices_);
    }


    template <int dim>
    bool
    FaceGeometry<dim>::contains_unit_point(const Point<dim - 1> &unit,
                                           const double tolerance) const
    {
      for (unsigned int d = 0; d + 1 < dim; ++d)
        if (unit[d] < -tolerance ||
            (shape_ != Shape::triangle && unit[d] > 1 + tolerance))
          return false;
      if (shape_ == Shape::triangle)
        return unit[0] + unit[dim - 2] <= 1 + tolerance;
      return true;
    }


    template <int dim>
    typename FaceGeometry<dim>::Projection
    FaceGeometry<dim>::project(const Point<dim> &x, const bool clamp) const
    {
      switch (shape_)
      {
        case Shape::segment:
          return project_on_segment(x, clamp);
        case Shape::triangle:
          return project_on_triangle(x, clamp);
        default:
          return project_on_quadrilateral(x, clamp);
      }
    }


    template <int dim>
    Quadrature<dim - 1>
    FaceGeometry<dim>::reference_quadrature(
      const unsigned int n_points_1d) const
    {
      Assert(n_points_1d > 0, ExcMessage("at least one point"));
      if (shape_ == Shape::triangle)
        return QGaussSimplex<dim - 1>(n_points_1d);
      return QGauss<dim - 1>(n_points_1d);
    }


    template <int dim>
    Point<dim - 1>
    FaceGeometry<dim>::unit_vertex(const unsigned int v) const
    {
      AssertIndexRange(v, vertices_.size());
      Point<dim - 1> unit;
      if (shape_ == Shape::segment)
        unit[0] = v;
      else if (shape_ == Shape::triangle)
      {
        if (v == 1)
          unit[0] = 1;
        else if (v == 2)
          unit[dim - 2] = 1;
      }
      else
      {
        unit[0]       = v % 2;
        unit[dim - 2] = v / 2;
      }
      return unit;
    }


    template <int dim>
    void
    FaceGeometry<dim>::closer_on_edge(const unsigned int a,
                                      const unsigned int b,
                                      const Point<dim>  &x,
                                      Projection        &best) const
    {
      const Tensor<1, dim> edge = vertices_[b] - vertices_[a];
      const double         t =
        std::clamp(((x - vertices_[a]) * edge) / (edge * edge), 0., 1.);
      const Point<dim - 1> ua = unit_vertex(a);
      const Projection     candidate =
        projection_at(ua + t * (unit_vertex(b) - ua), x);
      if (candidate.distance_square < best.distance_square)
        best = candidate;
    }


    template <int dim>
    typename FaceGeometry<dim>::Projection
    FaceGeometry<dim>::projection_at(const Point<dim - 1> &unit,
                                     const Point<dim>     &x) const
    {
      Projection p;
      p.unit            = unit;
      p.point           = point(unit);
      p.normal          = unit_normal(unit);
      p.distance_square = (p.point - x).norm_square();
      return p;
    }


    template <int dim>
    typename FaceGeometry<dim>::Projection
    FaceGeometry<dim>::project_on_segment(const Point<dim> &x,
                                          const bool        clamp) const
    {
      const Tensor<1, dim> e = vertices_[1] - vertices_[0];
      double               s = ((x - vertices_[0]) * e) / (e * e);
      if (clamp)
        s = std::clamp(s, 0., 1.);
      Point<dim - 1> unit;
      unit[0] = s;
      return projection_at(unit, x);
    }


    template <int dim>
    typename FaceGeometry<dim>::Projection
    FaceGeometry<dim>::project_on_triangle(const Point<dim> &x,
                                           const bool        clamp) const
    {
      // the foot on the triangle's plane from the normal equations of
      // min |v0 + s a + r b - x|^2
      const Tensor<1, dim> a = vertices_[1] - vertices_[0];
      const Tensor<1, dim> b = vertices_[2] - vertices_[0];
      const Tensor<1, dim> d = x - vertices_[0];
      const double aa = a * a, ab = a * b, bb = b * b, ad = a * d, bd = b * d;
      const double det = aa * bb - ab * ab;
      Assert(det > 0, ExcMessage("degenerate triangle face"));
      Point<dim - 1> unit;
      unit[0]       = (bb * ad - ab * bd) / det;
      unit[dim - 2] = (aa * bd - ab * ad) / det;
      if (!clamp || contains_unit_point(unit))
        return projection_at(unit, x);
      // outside: the closest point lies on the boundary, the best of the
      // three edges (each a clamped segment projection)
      Projection best;
      best.distance_square = std::numeric_limits<double>::max();
      for (const auto &[a, b] :
           std::array<std::pair<unsigned int, unsigned int>, 3>{
             {{0, 1}, {1, 2}, {2, 0}}})
        closer_on_edge(a, b, x, best);
      return best;
    }


    template <int dim>
    typename FaceGeometry<dim>::Projection
    FaceGeometry<dim>::project_on_quadrilateral(const Point<dim> &x,
                                                const bool        clamp) const
    {
      // Gauss-Newton on min |X(s, r) - x|^2 from the centre, clamped to the
      // unit square after every step when asked to
      const std::vector<Point<dim>> &v = vertices_;
      double                         s = 0.5, r = 0.5;
      const unsigned int             max_iterations = clamp ? 20 : 50;
      for (unsigned int it = 0; it < max_iterations; ++it)
      {
        Point<dim - 1> unit;
        unit[0]                 = s;
        unit[dim - 2]           = r;
        const Tensor<1, dim> Xs = (v[1] - v[0]) * (1 - r) + (v[3] - v[2]) * r;
        const Tensor<1, dim> Xr = (v[2] - v[0]) * (1 - s) + (v[3] - v[1]) * s;
        const Tensor<1, dim> d  = point(unit) - x;
        const double         a = Xs * Xs, b = Xs * Xr, c = Xr * Xr;
        const double         gs = Xs * d, gr = Xr * d;
        const double         det = a * c - b * b;
        if (det <= 0)
          break;
        double s_new = s - (c * gs - b * gr) / det;
        double r_new = r - (a * gr - b * gs) / det;
        if (clamp)
        {
          s_new = std::clamp(s_new, 0., 1.);
          r_new = std::clamp(r_new, 0., 1.);
        }
        const bool done = std::abs(s_new - s) + std::abs(r_new - r) < 1e-14;
        s               = s_new;
        r               = r_new;
        if (done)
          break;
      }
      Point<dim - 1> unit;
      unit[0]         = s;
      unit[dim - 2]   = r;
      Projection best = projection_at(unit, x);
      // clamped Gauss-Newton can stop at a boundary point that is not the
      // closest one on a warped face (the step points out of the square
      // along a direction that is not the edge's); the edges of a bilinear
      // face are straight, so the best point of the boundary is the best
      // of four segment projections
      const bool on_boundary = s == 0. || s == 1. || r == 0. || r == 1.;
      if (clamp && on_boundary)
        // the edges s = 0, s = 1, r = 0, r = 1
        for (const auto &[a, b] :
             std::array<std::pair<unsigned int, unsigned int>, 4>{
               {{0, 2}, {1, 3}, {0, 1}, {2, 3}}})
          closer_on_edge(a, b, x, best);
      return best;
    }


    template <int dim>
    typename FaceGeometry<dim>::LineIntersection
    FaceGeometry<dim>::intersect_line(const Point<dim>     &x,
                                      const Tensor<1, dim> &direction) const
    {
      LineIntersection result;
      for (unsigned int d = 0; d + 1 < dim; ++d)
        result.unit[d] = shape_ == Shape::triangle ? 1. / 3 : 0.5;
      // bilinear faces: quadratic convergence from the centre; 50 steps
      // only guard against a line that grazes a warped face
      for (unsigned int it = 0; it < 50; ++it)
      {
        const std::array<Tensor<1, dim>, dim - 1> t = tangents(result.unit);
        Tensor<2, dim>                            jacobian;
        double                                    scale = direction.norm();
        for (unsigned int r = 0; r < dim; ++r)
        {
          for (unsigned int k = 0; k + 1 < dim; ++k)
            jacobian[r][k] = t[k][r];
          jacobian[r][dim - 1] = -direction[r];
        }
        for (unsigned int k = 0; k + 1 < dim; ++k)
          scale *= t[k].norm();
        // parallel to the face (relative to the columns' lengths)
        if (!(std::abs(determinant(jacobian)) > 1e-12 * scale))
          return result;
        const Tensor<1, dim> residual =
          point(result.unit) - x - result.t * direction;
        const Tensor<1, dim> step   = invert(jacobian) * residual;
        double               change = 0;
        for (unsigned int k = 0; k + 1 < dim; ++k)
        {
          result.unit[k] -= step[k];
          change += std::abs(step[k]);
        }
        result.t -= step[dim - 1];
        if (change < 1e-14)
        {
          result.found = true;
          return result;
        }
      }
      return result;
    }


    template class FaceGeometry<2>;
    template class FaceGeometry<3>;
  } // namespace contact
} // namespace dualcontact
