#include <contact/face_geometry.h>
#include <contact/master_surface.h>

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    namespace
    {
      /** Squared distance from @p x to the box @p box (0 inside). */
      template <int dim>
      double
      distance_square_to_box(const Point<dim> &x, const BoundingBox<dim> &box)
      {
        double d2 = 0;
        for (unsigned int d = 0; d < dim; ++d)
        {
          const double below = box.lower_bound(d) - x[d];
          const double above = x[d] - box.upper_bound(d);
          const double out   = std::max({0., below, above});
          d2 += out * out;
        }
        return d2;
      }
    } // namespace


    template <int dim>
    MasterSurface<dim>::MasterSurface(const fem::ElasticBody<dim> &master,
                                      const types::boundary_id     boundary_id,
                                      const std::string           &pair_name)
    {
      // on a distributed mesh the faces of the owned cells: the search
      // over the processes' surfaces is ContactDiscretization's
      for (const auto &cell : master.dof_handler().active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if ((!master.is_distributed() || cell->is_locally_owned()) &&
              cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() == boundary_id)
          {
            Face face{cell, f, {}, cell->center()};
            for (const unsigned int v : cell->face(f)->vertex_indices())
              face.vertices.push_back(cell->face(f)->vertex(v));
            faces_.push_back(face);
          }
      const unsigned long n_faces =
        master.is_distributed() ?
          Utilities::MPI::sum<unsigned long>(faces_.size(),
                                             master.communicator()) :
          faces_.size();
      AssertThrow(n_faces > 0,
                  ExcMessage("Contact pair `" + pair_name +
                             "': the master body `" + master.name() +
                             "' has no boundary with id " +
                             std::to_string(boundary_id) + "."));
      std::vector<Leaf> leaves;
      leaves.reserve(faces_.size());
      double largest_diagonal = 0;
      for (unsigned int f = 0; f < faces_.size(); ++f)
      {
        leaves.emplace_back(BoundingBox<dim>(faces_[f].vertices), f);
        largest_diagonal =
          std::max(largest_diagonal,
                   leaves.back().first.vertex(0).distance(
                     leaves.back().first.vertex(
                       GeometryInfo<dim>::vertices_per_cell - 1)));
      }
      margin_square_ = std::pow(1e-10 * largest_diagonal, 2);
      if (!leaves.empty())
        tree_ = pack_rtree(leaves);
    }


    template <int dim>
    unsigned int
    MasterSurface<dim>::n_faces() const
    {
      return faces_.size();
    }


    template <int dim>
    const typename MasterSurface<dim>::Face &
    MasterSurface<dim>::face(const unsigned int f) const
    {
      AssertIndexRange(f, faces_.size());
      return faces_[f];
    }


    template <int dim>
    typename MasterSurface<dim>::Projection
    MasterSurface<dim>::closest_face(const Point<dim> &x) const
    {
      Assert(!faces_.empty(), ExcInternalError());
      namespace bgi = boost::geometry::index;
      Projection best;
      best.distance_square = std::numeric_limits<double>::max();
      const auto consider  = [&](const unsigned int f)
      {
        Point<dim>     closest;
        Tensor<1, dim> normal;
        const double   d2 =
          project_on_face(faces_[f].vertices, x, closest, normal);
        // the lowest index among equal distances, as a loop over the faces
        if (d2 < best.distance_square ||
            (d2 == best.distance_square && f < best.face))
        {
          best.face            = f;
          best.distance_square = d2;
          best.point           = closest;
          if (normal * (closest - faces_[f].cell_center) < 0)
            normal *= -1;
          best.outward_normal = normal;
        }
      };
      // the face of the nearest box bounds the distance; then every face
      // whose box meets the cube of that half-width around x (with margins
      // for the rounding of the distances: a node on an edge is equally far
      // from the faces that share it)
      std::vector<Leaf> nearest;
      tree_.query(bgi::nearest(x, 1), std::back_inserter(nearest));
      consider(nearest.front().second);
      const double reach =
        std::sqrt(best.distance_square * (1. + 1e-10) + margin_square_);
      Point<dim> lower = x, upper = x;
      for (unsigned int d = 0; d < dim; ++d)
      {
        lower[d] -= reach;
        upper[d] += reach;
      }
      std::vector<Leaf> candidates;
      tree_.query(bgi::intersects(
                    BoundingBox<dim>(std::make_pair(lower, upper))),
                  std::back_inserter(candidates));
      for (const Leaf &candidate : candidates)
        if (distance_square_to_box(x, candidate.first) <=
            best.distance_square * (1. + 1e-10) + margin_square_)
          consider(candidate.second);
      return best;
    }


    template <int dim>
    std::vector<unsigned int>
    MasterSurface<dim>::faces_in_box(const BoundingBox<dim> &box) const
    {
      namespace bgi = boost::geometry::index;
      std::vector<Leaf> leaves;
      if (!faces_.empty())
        tree_.query(bgi::intersects(box), std::back_inserter(leaves));
      std::vector<unsigned int> faces;
      for (const Leaf &leaf : leaves)
        faces.push_back(leaf.second);
      std::sort(faces.begin(), faces.end());
      return faces;
    }


    template <int dim>
    double
    MasterSurface<dim>::project_on_face(const std::vector<Point<dim>> &v,
                                        const Point<dim>              &x,
                                        Point<dim>                    &closest,
                                        Tensor<1, dim>                &normal)
    {
      const typename FaceGeometry<dim>::Projection projection =
        FaceGeometry<dim>(v).project(x);
      closest = projection.point;
      normal  = projection.normal;
      return projection.distance_square;
    }


    template class MasterSurface<2>;
    template class MasterSurface<3>;
  } // namespace contact
} // namespace dualcontact
