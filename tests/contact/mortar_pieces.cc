// The pieces of the dual mortar coupling (issue 44):
//  - DualBasis: biorthogonal to the vertex functions, int psi_j phi_k ds =
//    delta_jk int phi_j ds (1e-13), on a segment, a triangle and a warped
//    quadrilateral (there in the 3-point rule DualBasis integrates with:
//    the area element of a warped face is not a polynomial); on a segment psi =
//    (1 -/+ 3 xi) / 2, on a triangle (3 - 4 xi - 4 eta, 4 xi - 1, 4 eta - 1)
//    (1e-13);
//  - ConvexClipping: the overlap of two unit squares shifted by (0.3, 0.6)
//    has area 0.7 * 0.4, of a square and a triangle the clipped area by
//    hand (1e-14), of two intervals their common part; squares sharing an
//    edge give no sliver; the fan quadrature integrates x^2 y exactly;
//  - FaceGeometry::intersect_line: on a warped quadrilateral the point met
//    lies on the line and is X(unit) (1e-12).

#include <deal.II/base/quadrature_lib.h>

#include <contact/convex_clipping.h>
#include <contact/dual_basis.h>
#include <contact/face_geometry.h>

#include <test_tools.h>

#include <cmath>
#include <iostream>
#include <string>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

namespace
{
  /** max |int psi_j phi_k ds - delta_jk int phi_j ds| on @p face. */
  template <int dim>
  double
  biorthogonality_error(const contact::FaceGeometry<dim> &face)
  {
    const contact::DualBasis<dim> psi(face);
    const Quadrature<dim - 1>     quadrature = face.reference_quadrature(3);
    const unsigned int            n          = face.n_vertices();
    double                        error      = 0;
    for (unsigned int j = 0; j < n; ++j)
      for (unsigned int k = 0; k < n; ++k)
      {
        double psi_phi = 0, phi = 0;
        for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          const Point<dim - 1> &x = quadrature.point(q);
          const double          jxw =
            quadrature.weight(q) * face.jacobian_determinant(x);
          psi_phi += psi.value(j, x) * face.shape_value(k, x) * jxw;
          phi += face.shape_value(j, x) * jxw;
        }
        error = std::max(error, std::abs(psi_phi - (j == k ? phi : 0.)));
      }
    return error;
  }


  void
  check_dual_basis()
  {
    const contact::FaceGeometry<2> segment(
      {Point<2>(0.2, 0.1), Point<2>(1.4, 0.6)});
    check(biorthogonality_error(segment) < 1e-13,
          "segment: biorthogonality",
          biorthogonality_error(segment));
    const contact::DualBasis<2> psi_segment(segment);
    double                      closed_form = 0;
    for (const double s : {0., 0.3, 0.8, 1.})
    {
      const double xi = 2 * s - 1;
      closed_form     = std::max(
        {closed_form,
             std::abs(psi_segment.value(0, Point<1>(s)) - (1 - 3 * xi) / 2),
             std::abs(psi_segment.value(1, Point<1>(s)) - (1 + 3 * xi) / 2)});
    }
    check(closed_form < 1e-13, "segment: psi = (1 -/+ 3 xi) / 2", closed_form);

    const contact::FaceGeometry<3> triangle(
      {Point<3>(0, 0, 0), Point<3>(2, 0, 0.5), Point<3>(0.3, 1, 0)});
    check(biorthogonality_error(triangle) < 1e-13,
          "triangle: biorthogonality",
          biorthogonality_error(triangle));
    const contact::DualBasis<3> psi_triangle(triangle);
    const Point<2>              x(0.2, 0.3);
    const double                triangle_error =
      std::max({std::abs(psi_triangle.value(0, x) - (3 - 4 * x[0] - 4 * x[1])),
                std::abs(psi_triangle.value(1, x) - (4 * x[0] - 1)),
                std::abs(psi_triangle.value(2, x) - (4 * x[1] - 1))});
    check(triangle_error < 1e-13,
          "triangle: psi = (3 - 4 xi - 4 eta, 4 xi - 1, 4 eta - 1)",
          triangle_error);

    const contact::FaceGeometry<3> warped({Point<3>(0, 0, 0),
                                           Point<3>(1.2, 0, 0.1),
                                           Point<3>(0, 0.8, -0.1),
                                           Point<3>(1.5, 1.1, 0.3)});
    check(biorthogonality_error(warped) < 1e-13,
          "warped quadrilateral: biorthogonality",
          biorthogonality_error(warped));
  }


  double
  area(const std::vector<Point<2>> &polygon)
  {
    return std::abs(contact::ConvexClipping::twice_signed_area(polygon)) / 2;
  }


  void
  check_clipping()
  {
    using contact::ConvexClipping;
    const std::vector<Point<2>> square{Point<2>(0, 0),
                                       Point<2>(1, 0),
                                       Point<2>(1, 1),
                                       Point<2>(0, 1)};
    std::vector<Point<2>>       shifted;
    for (const Point<2> &p : square)
      shifted.push_back(p + Point<2>(0.3, 0.6));
    const auto overlap = ConvexClipping::overlap<2>(square, shifted, 1e-12);
    check(std::abs(area(overlap) - 0.7 * 0.4) < 1e-14,
          "squares: overlap area",
          area(overlap));
    // the triangle (0.5, -0.5), (1.5, 0.5), (0.5, 1.5) spans y in
    // [x - 1, 2 - x] for x in [0.5, 1.5]: within the square that is all of
    // [0.5, 1] x [0, 1], area 0.5 (its three edges cut the square's)
    const std::vector<Point<2>> triangle{Point<2>(0.5, -0.5),
                                         Point<2>(1.5, 0.5),
                                         Point<2>(0.5, 1.5)};
    const auto cut = ConvexClipping::overlap<2>(square, triangle, 1e-12);
    check(std::abs(area(cut) - 0.5) < 1e-14,
          "square and triangle: overlap area",
          area(cut));
    std::vector<Point<2>> neighbour;
    for (const Point<2> &p : square)
      neighbour.push_back(p + Point<2>(1, 0));
    check(ConvexClipping::overlap<2>(square, neighbour, 1e-12).empty(),
          "squares sharing an edge: no overlap",
          0);
    // int over the overlap [0.3, 1] x [0.6, 1] of x^2 y
    const Quadrature<2> rule     = ConvexClipping::quadrature<2>(overlap, 3);
    double              integral = 0;
    for (unsigned int q = 0; q < rule.size(); ++q)
      integral +=
        rule.weight(q) * rule.point(q)[0] * rule.point(q)[0] * rule.point(q)[1];
    const double exact = (1 - 0.027) / 3 * (1 - 0.36) / 2;
    check(std::abs(integral - exact) < 1e-14,
          "fan quadrature: int x^2 y",
          integral - exact);
    const auto interval =
      ConvexClipping::overlap<1>({Point<1>(0.5), Point<1>(-1)},
                                 {Point<1>(0.2), Point<1>(2)},
                                 1e-12);
    check(interval.size() == 2 && interval[0][0] == 0.2 &&
            interval[1][0] == 0.5,
          "intervals: common part [0.2, 0.5]",
          interval.size());
  }


  void
  check_intersect_line()
  {
    const contact::FaceGeometry<3> warped({Point<3>(0, 0, 0),
                                           Point<3>(1.2, 0, 0.1),
                                           Point<3>(0, 0.8, -0.1),
                                           Point<3>(1.5, 1.1, 0.3)});
    const Point<3>                 x(0.7, 0.4, 1.3);
    const Tensor<1, 3>             direction({0.1, -0.2, -1});
    const auto                     hit = warped.intersect_line(x, direction);
    const Tensor<1, 3> miss = warped.point(hit.unit) - (x + hit.t * direction);
    check(hit.found && miss.norm() < 1e-12,
          "intersect_line: warped quadrilateral",
          miss.norm());
  }
} // namespace


int
main()
{
  try
  {
    check_dual_basis();
    check_clipping();
    check_intersect_line();
  }
  catch (const std::exception &e)
  {
    std::cerr << "exception: " << e.what() << std::endl;
    return 1;
  }
  return test_tools::finish();
}
