// The master-face search through the R-tree (contact::MasterSurface) gives
// what the loop over all faces gives: the same face (the lowest index among
// equally distant ones), bit for bit the same distance and point.  On
// curved master surfaces (the boundary of a ball, refined twice: bilinear
// faces that are not plane in 3D) and on a flat one (a box face: the
// faces' boxes are flat, and nodes on edges and vertices are equally far
// from two to four faces), for random points about the surface and for the
// faces' vertices, edge midpoints and centres, in 2D and 3D.

#include <deal.II/base/geometry_info.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <contact/master_surface.h>
#include <fem/elastic_body.h>

#include <test_tools.h>

#include <iostream>
#include <limits>
#include <random>
#include <string>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

namespace
{
  /** The projection of a loop over all faces, lowest index on ties. */
  template <int dim>
  typename contact::MasterSurface<dim>::Projection
  closest_by_loop(const contact::MasterSurface<dim> &surface,
                  const Point<dim>                  &x)
  {
    typename contact::MasterSurface<dim>::Projection best;
    best.distance_square = std::numeric_limits<double>::max();
    for (unsigned int f = 0; f < surface.n_faces(); ++f)
    {
      Point<dim>     closest;
      Tensor<1, dim> normal;
      const double   d2 = contact::MasterSurface<dim>::project_on_face(
        surface.face(f).vertices, x, closest, normal);
      if (d2 < best.distance_square)
      {
        best.face            = f;
        best.distance_square = d2;
        best.point           = closest;
      }
    }
    return best;
  }


  /** Points to search from: random ones in the box [-1.5, 1.5]^dim, and the
   * vertices, edge midpoints and centres of the faces. */
  template <int dim>
  std::vector<Point<dim>>
  search_points(const contact::MasterSurface<dim> &surface)
  {
    std::vector<Point<dim>>                points;
    std::mt19937                           random(17);
    std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
    for (unsigned int i = 0; i < 2000; ++i)
    {
      Point<dim> x;
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = coordinate(random);
      points.push_back(x);
    }
    for (unsigned int f = 0; f < surface.n_faces(); ++f)
    {
      const auto &v = surface.face(f).vertices;
      Point<dim>  centre;
      for (const Point<dim> &p : v)
      {
        points.push_back(p);
        centre += p / static_cast<double>(v.size());
      }
      points.push_back(centre);
      for (unsigned int a = 0; a < v.size(); ++a)
        for (unsigned int b = a + 1; b < v.size(); ++b)
          points.push_back(0.5 * (v[a] + v[b]));
    }
    return points;
  }


  template <int dim>
  void
  compare(const std::string &name, Triangulation<dim> &triangulation)
  {
    auto shared =
      std::shared_ptr<Triangulation<dim>>(&triangulation, [](auto *) {});
    for (const auto &cell : triangulation.active_cell_iterators())
      cell->set_material_id(0);
    fem::ElasticBody<dim> body(name,
                               shared,
                               1,
                               {{0, fem::IsotropicMaterial(1e9, 0.3)}});
    body.setup();
    const contact::MasterSurface<dim> surface(body, 0, name);

    unsigned int n_points = 0, n_different = 0;
    for (const Point<dim> &x : search_points(surface))
    {
      const auto tree = surface.closest_face(x);
      const auto loop = closest_by_loop(surface, x);
      ++n_points;
      if (tree.face != loop.face ||
          tree.distance_square != loop.distance_square ||
          tree.point != loop.point)
        ++n_different;
    }
    std::cout << name << ": " << surface.n_faces() << " faces" << std::endl;
    check(n_different == 0,
          name +
            ": points whose face, distance or point differ from the "
            "loop over all faces (of " +
            std::to_string(n_points) + ")",
          n_different);
  }
} // namespace


int
main()
{
  try
  {
    {
      Triangulation<2> ball;
      GridGenerator::hyper_ball(ball);
      ball.refine_global(3);
      compare<2>("2D ball", ball);
    }
    {
      Triangulation<3> ball;
      GridGenerator::hyper_ball(ball);
      ball.refine_global(2);
      compare<3>("3D ball", ball);
    }
    {
      // boundary id 0 of a colorized box is its face x = -1
      Triangulation<3> box;
      GridGenerator::subdivided_hyper_rectangle(
        box, {4, 6, 5}, Point<3>(-1, -1, -1), Point<3>(1, 1, 1), true);
      compare<3>("flat box face", box);
    }
    {
      // a boundary id the mesh does not have: the error names the pair
      Triangulation<2> square;
      GridGenerator::hyper_cube(square, 0, 1, true);
      for (const auto &cell : square.active_cell_iterators())
        cell->set_material_id(0);
      auto shared = std::shared_ptr<Triangulation<2>>(&square, [](auto *) {});
      fem::ElasticBody<2> body("square",
                               shared,
                               1,
                               {{0, fem::IsotropicMaterial(1e9, 0.3)}});
      body.setup();
      bool thrown = false;
      try
      {
        contact::MasterSurface<2> surface(body, 7, "pair A");
      }
      catch (const std::exception &error)
      {
        thrown = std::string(error.what()).find("pair A") != std::string::npos;
      }
      check(thrown,
            "a master boundary id the mesh lacks throws naming the pair",
            thrown);
    }
  }
  catch (const std::exception &error)
  {
    std::cerr << "Exception: " << error.what() << std::endl;
    return 1;
  }
  return test_tools::finish();
}
