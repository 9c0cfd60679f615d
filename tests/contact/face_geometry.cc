// contact::FaceGeometry, the one description of a boundary face that the
// contact search and the mortar integrals share: on a segment, a triangle
// and a (warped) bilinear quadrilateral, the vertex shape functions are a
// partition of unity that interpolates the vertices, their gradients match
// finite differences, the reference quadrature integrates the area and the
// shape functions exactly (parallelogram, triangle: area / n_vertices), and
// the clamped closest point agrees with a dense sampling of the face (never
// farther, within the sampling's resolution) while the unclamped one is the
// foot of the perpendicular on the extended face.

#include <contact/face_geometry.h>

#include <test_tools.h>

#include <cmath>
#include <iostream>
#include <random>
#include <string>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

namespace
{
  /** The closest of (n+1)^2 (n+1 in 2D) sample points of the face. */
  template <int dim>
  double
  sampled_distance_square(const contact::FaceGeometry<dim> &face,
                          const Point<dim>                 &x,
                          const unsigned int                n)
  {
    double best = std::numeric_limits<double>::max();
    for (unsigned int i = 0; i <= n; ++i)
      for (unsigned int j = 0; j <= (dim == 2 ? 0 : n); ++j)
      {
        Point<dim - 1> unit;
        unit[0] = double(i) / n;
        if constexpr (dim == 3)
          unit[1] = double(j) / n;
        if (!face.contains_unit_point(unit, 1e-12))
          continue;
        best = std::min(best, (face.point(unit) - x).norm_square());
      }
    return best;
  }


  template <int dim>
  void
  check_face(const std::string &name, const std::vector<Point<dim>> &vertices)
  {
    std::cout << name << std::endl;
    const contact::FaceGeometry<dim> face(vertices);
    const unsigned int               nv = face.n_vertices();

    // vertices interpolated, partition of unity at an interior point
    const Quadrature<dim - 1> quadrature = face.reference_quadrature(3);
    double                    worst      = 0;
    for (unsigned int q = 0; q < quadrature.size(); ++q)
    {
      double     sum = 0;
      Point<dim> x;
      for (unsigned int v = 0; v < nv; ++v)
      {
        sum += face.shape_value(v, quadrature.point(q));
        x += face.shape_value(v, quadrature.point(q)) * face.vertex(v);
      }
      worst = std::max({worst,
                        std::abs(sum - 1),
                        (x - face.point(quadrature.point(q))).norm()});
    }
    check(worst < 1e-14, "partition of unity, X = sum phi_v v", worst);

    // gradients against central differences
    double grad_error = 0;
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      for (unsigned int v = 0; v < nv; ++v)
        for (unsigned int d = 0; d + 1 < dim; ++d)
        {
          Point<dim - 1> plus = quadrature.point(q), minus = plus;
          plus[d] += 1e-6;
          minus[d] -= 1e-6;
          const double fd =
            (face.shape_value(v, plus) - face.shape_value(v, minus)) / 2e-6;
          grad_error =
            std::max(grad_error,
                     std::abs(fd - face.shape_grad(v, quadrature.point(q))[d]));
        }
    check(grad_error < 1e-8,
          "shape gradients = finite differences",
          grad_error);

    // integrals of 1 and of each shape function
    std::vector<double> integral(nv, 0.);
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      for (unsigned int v = 0; v < nv; ++v)
        integral[v] += face.shape_value(v, quadrature.point(q)) *
                       quadrature.weight(q) *
                       face.jacobian_determinant(quadrature.point(q));
    double total = 0, area = 0;
    for (const double w : integral)
      total += w;
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      area +=
        quadrature.weight(q) * face.jacobian_determinant(quadrature.point(q));
    check(std::abs(total - area) < 1e-14 * area,
          "sum of int phi_v ds = int 1 ds",
          total);
    // exact but on the warped face (a rule of another order there)
    check(std::abs(area - face.measure()) < 1e-4 * area,
          "int 1 ds = measure()",
          face.measure());
  }


  /** Clamped projections against sampling, unclamped against the
   * perpendicular condition, for random points around the face. */
  template <int dim>
  void
  check_projections(const std::vector<Point<dim>> &vertices, const double size)
  {
    const contact::FaceGeometry<dim>       face(vertices);
    std::mt19937                           random(7);
    std::uniform_real_distribution<double> offset(-size, size);
    double       worst_excess = 0, worst_tangential = 0, worst_gap = 0;
    unsigned int n_off_face = 0;
    for (unsigned int k = 0; k < 200; ++k)
    {
      Point<dim> x = face.center();
      for (unsigned int d = 0; d < dim; ++d)
        x[d] += offset(random);
      const auto   p       = face.project(x);
      const double sampled = sampled_distance_square(face, x, 400);
      // never farther than the best sample, and not much closer (the
      // sampling resolution, size / 400)
      worst_excess =
        std::max(worst_excess,
                 std::sqrt(p.distance_square) - std::sqrt(sampled));
      worst_gap =
        std::max(worst_gap, std::sqrt(sampled) - std::sqrt(p.distance_square));
      if (!face.contains_unit_point(p.unit, 1e-12))
        ++n_off_face;
      // unclamped: x - X(unit) is orthogonal to the tangents there
      const auto unclamped = face.project(x, false);
      for (const auto &t : face.tangents(unclamped.unit))
        worst_tangential =
          std::max(worst_tangential,
                   std::abs((x - unclamped.point) * t) / t.norm());
    }
    check(n_off_face == 0, "clamped projections on the face", n_off_face);
    check(worst_excess < 1e-12 * size,
          "clamped distance <= best of 400^2 samples",
          worst_excess);
    check(worst_gap < 2 * size / 400,
          "clamped distance within the sampling resolution",
          worst_gap);
    check(worst_tangential < 1e-10 * size,
          "unclamped: (x - X) orthogonal to the face",
          worst_tangential);
  }
} // namespace


int
main()
{
  check_face<2>("segment", {Point<2>(0.2, 0.1), Point<2>(1.4, 0.6)});
  check_projections<2>({Point<2>(0.2, 0.1), Point<2>(1.4, 0.6)}, 1.);

  const std::vector<Point<3>> triangle{Point<3>(0, 0, 0.1),
                                       Point<3>(1.2, 0.1, 0),
                                       Point<3>(0.3, 0.9, 0.2)};
  check_face<3>("triangle", triangle);
  check_projections<3>(triangle, 1.);
  {
    const contact::FaceGeometry<3> face(triangle);
    const Quadrature<2>            q  = face.reference_quadrature(2);
    double                         w0 = 0;
    for (unsigned int k = 0; k < q.size(); ++k)
      w0 += face.shape_value(0, q.point(k)) * q.weight(k) *
            face.jacobian_determinant(q.point(k));
    check(std::abs(w0 - face.measure() / 3) < 1e-14,
          "triangle: int phi_0 ds = area / 3",
          w0);
    const Tensor<1, 3> n = face.unit_normal(q.point(0));
    check(std::abs(n * (triangle[1] - triangle[0])) < 1e-14 &&
            std::abs(n * (triangle[2] - triangle[0])) < 1e-14,
          "triangle: normal orthogonal to its edges");
  }

  const std::vector<Point<3>> parallelogram{Point<3>(0, 0, 0),
                                            Point<3>(1, 0, 0.2),
                                            Point<3>(0.3, 1, 0),
                                            Point<3>(1.3, 1, 0.2)};
  check_face<3>("parallelogram", parallelogram);
  {
    const contact::FaceGeometry<3> face(parallelogram);
    const double area = cross_product_3d(parallelogram[1] - parallelogram[0],
                                         parallelogram[2] - parallelogram[0])
                          .norm();
    check(std::abs(face.measure() - area) < 1e-14,
          "parallelogram: measure = |a x b|",
          face.measure());
  }
  const std::vector<Point<3>> warped{Point<3>(0, 0, 0),
                                     Point<3>(1, 0, 0.15),
                                     Point<3>(0, 1, -0.1),
                                     Point<3>(1.1, 1.05, 0.3)};
  check_face<3>("warped quadrilateral", warped);
  check_projections<3>(warped, 1.);

  return test_tools::failures == 0 ? 0 : 1;
}
