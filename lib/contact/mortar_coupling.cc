#include <deal.II/base/bounding_box.h>
#include <deal.II/base/quadrature.h>

#include <contact/convex_clipping.h>
#include <contact/dual_basis.h>
#include <contact/mortar_coupling.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    namespace
    {
      /**
       * Gauss points per direction of the mortar rules: psi_j phi_l is of
       * degree 2 on segments and 4 on (bilinear) quadrilaterals, which 3
       * points (QGauss: degree 5; QGaussSimplex on the clipped polygon's
       * triangles: degree 5) integrate exactly on flat faces.
       */
      constexpr unsigned int n_mortar_points = 3;

      /** The centre of the reference face. */
      template <int dim>
      Point<dim - 1>
      reference_center(const FaceGeometry<dim> &face)
      {
        Point<dim - 1> unit;
        const bool     triangle =
          face.shape() == FaceGeometry<dim>::Shape::triangle;
        for (unsigned int d = 0; d + 1 < dim; ++d)
          unit[d] = triangle ? 1. / 3 : 0.5;
        return unit;
      }

      /** The face's vertices in cyclic order (a quadrilateral's vertices
       * are lexicographic in deal.II: 0, 1, 3, 2 around it). */
      template <int dim>
      std::vector<unsigned int>
      cyclic_vertices(const FaceGeometry<dim> &face)
      {
        if (face.shape() == FaceGeometry<dim>::Shape::quadrilateral)
          return {0, 1, 3, 2};
        std::vector<unsigned int> order(face.n_vertices());
        for (unsigned int v = 0; v < order.size(); ++v)
          order[v] = v;
        return order;
      }

      /** The largest distance between two vertices of the face [m]. */
      template <int dim>
      double
      diameter(const FaceGeometry<dim> &face)
      {
        double h = 0;
        for (const Point<dim> &a : face.vertices())
          for (const Point<dim> &b : face.vertices())
            h = std::max(h, a.distance(b));
        return h;
      }

      /** The face's unit normal at its centre, pointing away from the
       * centre @p cell_center of its cell. */
      template <int dim>
      Tensor<1, dim>
      outward_normal(const FaceGeometry<dim> &face,
                     const Point<dim>        &cell_center)
      {
        Tensor<1, dim> n = face.unit_normal(reference_center(face));
        if (n * (face.center() - cell_center) < 0)
          n *= -1;
        return n;
      }

      /**
       * The slave face's line (2D) or plane (3D) through its centre, with
       * an orthonormal frame: what the faces are projected onto.
       */
      template <int dim>
      struct AuxiliaryPlane
      {
        Point<dim>                          origin;
        std::array<Tensor<1, dim>, dim - 1> axes;

        AuxiliaryPlane(const FaceGeometry<dim> &face,
                       const Tensor<1, dim>    &normal)
            : origin(face.center())
        {
          Tensor<1, dim> t = face.vertex(1) - face.vertex(0);
          t -= (t * normal) * normal;
          axes[0] = t / t.norm();
          if constexpr (dim == 3)
            axes[1] = cross_product_3d(normal, axes[0]);
        }

        Point<dim - 1>
        coordinates(const Point<dim> &x) const
        {
          Point<dim - 1> p;
          for (unsigned int k = 0; k + 1 < dim; ++k)
            p[k] = (x - origin) * axes[k];
          return p;
        }

        Point<dim>
        point(const Point<dim - 1> &p) const
        {
          Point<dim> x = origin;
          for (unsigned int k = 0; k + 1 < dim; ++k)
            x += p[k] * axes[k];
          return x;
        }

        /** The face projected onto the plane, vertices in cyclic order. */
        std::vector<Point<dim - 1>>
        polygon(const FaceGeometry<dim> &face) const
        {
          std::vector<Point<dim - 1>> result;
          for (const unsigned int v : cyclic_vertices(face))
            result.push_back(coordinates(face.vertex(v)));
          return result;
        }
      };
    } // namespace


    template <int dim>
    MortarCoupling<dim>::MortarCoupling(const ContactPair<dim>      &pair,
                                        const fem::ElasticBody<dim> &slave,
                                        const fem::ElasticBody<dim> *master,
                                        const MasterSurface<dim>    *surface)
        : pair_(pair)
        , master_(master)
        , surface_(surface)
    {
      Assert(pair.obstacle || (master != nullptr && surface != nullptr),
             ExcInternalError());
      check_applicable(slave);
      for (const auto &cell : slave.dof_handler().active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() == pair.slave_boundary)
          {
            const auto                           face = cell->face(f);
            std::vector<Point<dim>>              vertices;
            std::vector<types::global_dof_index> keys;
            // the active face's vertices, hanging ones included
            for (const unsigned int v : face->vertex_indices())
            {
              vertices.push_back(face->vertex(v));
              keys.push_back(face->vertex_dof_index(v, 0));
              Row &row     = rows_[keys.back()];
              row.position = face->vertex(v);
              for (unsigned int c = 0; c < dim; ++c)
                row.dofs[c] = face->vertex_dof_index(v, c);
            }
            const FaceGeometry<dim>   geometry(vertices);
            const Quadrature<dim - 1> quadrature =
              geometry.reference_quadrature(n_mortar_points);
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              for (unsigned int v = 0; v < keys.size(); ++v)
                rows_[keys[v]].support +=
                  geometry.shape_value(v, quadrature.point(q)) *
                  quadrature.weight(q) *
                  geometry.jacobian_determinant(quadrature.point(q));
            if (pair.obstacle)
              integrate_on_obstacle(geometry, keys);
            else
              integrate_on_master(geometry,
                                  outward_normal(geometry, cell->center()),
                                  keys);
          }
      AssertThrow(!rows_.empty(),
                  ExcMessage("Contact pair `" + pair.name +
                             "': the slave body `" + slave.name() +
                             "' has no boundary with id " +
                             std::to_string(pair.slave_boundary) + "."));
      for (auto &[key, row] : rows_)
      {
        if (!pair.obstacle)
        {
          row.covered = 0;
          for (const auto &[l, node] : row.master)
          {
            row.covered += node.value;
            row.gap_vector += node.value * node.position;
          }
          row.gap_vector -= row.covered * row.position;
        }
        row.slave[key] = {row.dofs, row.covered};
      }
      condense_hanging_nodes(slave.hanging_node_constraints());
    }


    template <int dim>
    void
    MortarCoupling<dim>::condense_hanging_nodes(
      const AffineConstraints<double> &hanging)
    {
      for (auto it = rows_.begin(); it != rows_.end();)
      {
        const auto *line = hanging.get_constraint_entries(it->first);
        if (!hanging.is_constrained(it->first) || line == nullptr)
        {
          ++it;
          continue;
        }
        const Row &h = it->second;
        for (const auto &[parent, c] : *line)
        {
          const auto to = rows_.find(parent);
          // the parents are the vertices of the coarse face's edge: slave
          // boundary vertices, never hanging themselves (1-irregular mesh)
          AssertThrow(to != rows_.end() && !hanging.is_constrained(parent),
                      ExcMessage("Contact pair `" + pair_.name +
                                 "': a hanging slave node whose parent is no "
                                 "slave vertex (Discretization = mortar)."));
          Row &j = to->second;
          j.support += c * h.support;
          j.covered += c * h.covered;
          j.gap_vector += c * h.gap_vector;
          j.weighted_gap += c * h.weighted_gap;
          for (const auto &[l, node] : h.master)
          {
            MasterNode &m = j.master[l];
            m.dofs        = node.dofs;
            m.position    = node.position;
            m.value += c * node.value;
          }
          for (const auto &[k, term] : h.slave)
          {
            SlaveTerm &s = j.slave[k];
            s.dofs       = term.dofs;
            s.value += c * term.value;
          }
        }
        it = rows_.erase(it);
      }
    }


    template <int dim>
    void
    MortarCoupling<dim>::check_applicable(
      const fem::ElasticBody<dim> &slave) const
    {
      const std::string name = "Contact pair `" + pair_.name + "'";
      for (const fem::ElasticBody<dim> *body : {&slave, master_})
        if (body != nullptr)
        {
          AssertThrow(body->fe().degree == 1,
                      ExcMessage(name +
                                 ": Discretization = mortar needs faces of "
                                 "degree 1 (`Finite element degree = 1'): the "
                                 "dual basis of degree-2 faces needs Popp's "
                                 "basis transformation (their vertex "
                                 "integrals vanish or change sign), which is "
                                 "not implemented; use Discretization = node "
                                 "to segment."));
          AssertThrow(!body->is_distributed(),
                      ExcMessage(
                        name +
                        ": Discretization = mortar does not run on "
                        "distributed meshes yet (body `" +
                        body->name() +
                        "'; the master faces near each slave face would "
                        "have to be gathered first): use a replicated "
                        "mesh, or Discretization = node to segment."));
        }
    }


    template <int dim>
    void
    MortarCoupling<dim>::integrate_on_master(
      const FaceGeometry<dim>                    &face,
      const Tensor<1, dim>                       &normal,
      const std::vector<types::global_dof_index> &keys)
    {
      const DualBasis<dim>      psi(face);
      const AuxiliaryPlane<dim> plane(face, normal);
      const double              h = diameter(face);
      // the master faces within reach: those near the closest one (the
      // gap there, plus a face size for the faces around it)
      const double reach = std::min(
        pair_.search_distance,
        std::sqrt(surface_->closest_face(face.center()).distance_square) + h);
      BoundingBox<dim> box = face.bounding_box();
      box.extend(reach);
      const std::vector<Point<dim - 1>> slave_polygon = plane.polygon(face);
      for (const unsigned int f : surface_->faces_in_box(box))
      {
        const typename MasterSurface<dim>::Face &master_face =
          surface_->face(f);
        const FaceGeometry<dim> master(master_face.vertices);
        // a face seen from behind (the far side of a thin master) is not
        // where the slave face touches
        if (outward_normal(master, master_face.cell_center) * normal >= 0)
          continue;
        const std::vector<Point<dim - 1>> region =
          ConvexClipping::overlap<dim - 1>(slave_polygon,
                                           plane.polygon(master),
                                           1e-10 * h);
        if (region.size() < dim)
          continue;
        const auto master_dofs_face =
          master_face.cell->face(master_face.face_no);
        std::vector<std::array<types::global_dof_index, dim>> dofs(
          master.n_vertices());
        for (unsigned int l = 0; l < master.n_vertices(); ++l)
          for (unsigned int c = 0; c < dim; ++c)
            dofs[l][c] = master_dofs_face->vertex_dof_index(l, c);
        const Quadrature<dim - 1> quadrature =
          ConvexClipping::quadrature<dim - 1>(region, n_mortar_points);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          const Point<dim> x         = plane.point(quadrature.point(q));
          const auto       on_slave  = face.intersect_line(x, normal);
          const auto       on_master = master.intersect_line(x, normal);
          if (!on_slave.found || !on_master.found)
            continue;
          // the plane's area element to the slave face's
          const double ds = quadrature.weight(q) /
                            std::abs(face.unit_normal(on_slave.unit) * normal);
          for (unsigned int j = 0; j < keys.size(); ++j)
          {
            const double psi_ds = psi.value(j, on_slave.unit) * ds;
            for (unsigned int l = 0; l < master.n_vertices(); ++l)
            {
              MasterNode &node = rows_[keys[j]].master[dofs[l][0]];
              node.dofs        = dofs[l];
              node.position    = master.vertex(l);
              node.value += psi_ds * master.shape_value(l, on_master.unit);
            }
          }
        }
      }
    }


    template <int dim>
    void
    MortarCoupling<dim>::integrate_on_obstacle(
      const FaceGeometry<dim>                    &face,
      const std::vector<types::global_dof_index> &keys)
    {
      const DualBasis<dim>      psi(face);
      const Quadrature<dim - 1> quadrature =
        face.reference_quadrature(n_mortar_points);
      for (unsigned int q = 0; q < quadrature.size(); ++q)
      {
        const Point<dim> x = face.point(quadrature.point(q));
        Point<dim>       closest;
        Tensor<1, dim>   outward;
        pair_.obstacle->project(x, closest, outward);
        // the signed distance, as node-to-segment's nodal gap
        const double gap = (x - closest) * outward;
        const double ds =
          quadrature.weight(q) * face.jacobian_determinant(quadrature.point(q));
        for (unsigned int j = 0; j < keys.size(); ++j)
        {
          const double psi_ds = psi.value(j, quadrature.point(q)) * ds;
          rows_[keys[j]].weighted_gap += psi_ds * gap;
          rows_[keys[j]].covered += psi_ds;
        }
      }
    }


    template <int dim>
    bool
    MortarCoupling<dim>::place(const types::global_dof_index key,
                               const Tensor<1, dim>         &weighted_normal,
                               ContactNode<dim>             &node,
                               MasterEntries                &master) const
    {
      const auto found = rows_.find(key);
      if (found == rows_.end())
        return false;
      const Row &row = found->second;
      if (!(row.covered >= pair_.mortar_coverage * row.support))
        return false;
      // the slave side divided by S~_j: the node's own coefficient, the
      // hanging nodes condensed into it (1 and none without them)
      for (const auto &[k, term] : row.slave)
        if (k == key)
          master.own = term.value / row.covered;
        else
          for (unsigned int c = 0; c < dim; ++c)
          {
            master.entries.push_back(
              {pair_.slave_body, term.dofs[c], -term.value / row.covered});
            master.components.push_back(c);
          }
      if (pair_.obstacle)
      {
        Tensor<1, dim> outward;
        pair_.obstacle->project(node.position, node.master_point, outward);
        node.normal = -outward;
        return (node.position - node.master_point).norm() <=
               pair_.search_distance;
      }
      node.normal = weighted_normal / weighted_normal.norm();
      for (const auto &[l, m] : row.master)
        for (unsigned int c = 0; c < dim; ++c)
        {
          master.entries.push_back(
            {pair_.master_body, m.dofs[c], m.value / row.covered});
          master.components.push_back(c);
        }
      return true;
    }


    template <int dim>
    double
    MortarCoupling<dim>::gap(const types::global_dof_index key,
                             const Tensor<1, dim>         &normal) const
    {
      const Row &row = rows_.at(key);
      return (pair_.obstacle ? row.weighted_gap : normal * row.gap_vector) /
             row.covered;
    }


    template <int dim>
    const std::map<types::global_dof_index, typename MortarCoupling<dim>::Row> &
    MortarCoupling<dim>::rows() const
    {
      return rows_;
    }


    template class MortarCoupling<2>;
    template class MortarCoupling<3>;
  } // namespace contact
} // namespace dualcontact
