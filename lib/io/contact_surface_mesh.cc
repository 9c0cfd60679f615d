#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/affine_constraints.h>

#include <io/contact_surface_mesh.h>

#include <cmath>
#include <map>

namespace dualcontact
{
  namespace io
  {
    namespace
    {
      /**
       * The directions spanning face @p face of the unit cell (increasing),
       * and whether listing the face's points lexicographically in them
       * runs counter-clockwise seen from outside (3D; the cross product of
       * the two directions is the outward normal).
       */
      template <int dim>
      std::pair<std::array<unsigned int, dim - 1>, bool>
      face_directions(const unsigned int face)
      {
        const unsigned int                normal = face / 2;
        std::array<unsigned int, dim - 1> directions;
        for (unsigned int d = 0, k = 0; d < dim; ++d)
          if (d != normal)
            directions[k++] = d;
        // e_a x e_b = +e_normal except for normal = 1 (e_0 x e_2 = -e_1);
        // the outward normal is +e_normal on odd faces, -e_normal on even
        const int cross   = normal == 1 ? -1 : 1;
        const int outward = face % 2 == 1 ? 1 : -1;
        return {directions, cross * outward > 0};
      }
    } // namespace


    template <int dim>
    ContactSurfaceMesh<dim>::ContactSurfaceMesh(
      const fem::ElasticBody<dim>                        &slave,
      const dealii::types::boundary_id                    boundary_id,
      const std::vector<dealii::types::global_dof_index> &node_dofs)
    {
      std::map<dealii::types::global_dof_index, unsigned int> node_of_dof;
      for (unsigned int i = 0; i < node_dofs.size(); ++i)
        node_of_dof[node_dofs[i]] = i;
      dealii::AffineConstraints<double> hanging;
      dealii::DoFTools::make_hanging_node_constraints(slave.dof_handler(),
                                                      hanging);
      hanging.close();
      const auto combination_of = [&](const dealii::types::global_dof_index dof)
      {
        Combination combination;
        if (const auto node = node_of_dof.find(dof); node != node_of_dof.end())
          return Combination{{node->second, 1.}};
        if (!hanging.is_constrained(dof))
          return combination;
        for (const auto &[parent, coefficient] :
             *hanging.get_constraint_entries(dof))
        {
          const auto node = node_of_dof.find(parent);
          if (node == node_of_dof.end())
            return Combination();
          combination.emplace_back(node->second, coefficient);
        }
        return combination;
      };

      if (slave.cell_family().is_simplex())
      {
        add_simplex_faces(slave, boundary_id, combination_of);
        return;
      }
      const dealii::FESystem<dim>          &fe     = slave.fe();
      const dealii::FiniteElement<dim>     &base   = fe.base_element(0);
      const unsigned int                    degree = base.degree;
      const std::vector<dealii::Point<dim>> unit_points =
        base.get_unit_support_points();
      const unsigned int n_per_face = std::pow(degree + 1, dim - 1);
      std::map<dealii::types::global_dof_index, unsigned int> point_of_dof;
      std::vector<dealii::types::global_dof_index>            cell_dofs(
        fe.n_dofs_per_cell());

      for (const auto &cell : slave.dof_handler().active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
        {
          if (cell->is_artificial() || !cell->face(f)->at_boundary() ||
              cell->face(f)->boundary_id() != boundary_id)
            continue;
          cell->get_dof_indices(cell_dofs);
          const auto [directions, counter_clockwise] = face_directions<dim>(f);
          // the face's support points on a (degree + 1)^(dim - 1) grid, by
          // their coordinates in the unit cell (independent of the face's
          // orientation)
          std::vector<dealii::types::global_dof_index> grid(n_per_face);
          std::vector<dealii::Point<dim>>              grid_unit(n_per_face);
          for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
            if (fe.system_to_component_index(k).first == 0 &&
                fem::CellFamily<dim>::is_face_dof(fe, k, f))
            {
              const dealii::Point<dim> &xi =
                unit_points[fe.system_to_component_index(k).second];
              unsigned int index = 0;
              for (int d = dim - 2; d >= 0; --d)
                index = index * (degree + 1) +
                        std::lround(xi[directions[d]] * degree);
              grid[index]      = cell_dofs[k];
              grid_unit[index] = xi;
            }
          const auto point_of = [&](const unsigned int index)
          {
            const auto [it, inserted] =
              point_of_dof.emplace(grid[index], positions_.size());
            if (inserted)
            {
              positions_.push_back(
                slave.mapping().transform_unit_to_real_cell(cell,
                                                            grid_unit[index]));
              combinations_.push_back(combination_of(grid[index]));
            }
            return it->second;
          };
          const auto add_cell = [&](const Cell &grid_indices)
          {
            bool carries_contact = false;
            for (const unsigned int index : grid_indices)
              carries_contact =
                carries_contact || !combination_of(grid[index]).empty();
            if (!carries_contact)
              return;
            Cell points(grid_indices.size());
            for (unsigned int v = 0; v < points.size(); ++v)
              points[v] = point_of(grid_indices[v]);
            cells_.push_back(points);
            owners_.push_back(cell->subdomain_id());
          };
          if constexpr (dim == 2)
            for (unsigned int i = 0; i < degree; ++i)
              add_cell(Cell{{i, i + 1}});
          else
            for (unsigned int j = 0; j < degree; ++j)
              for (unsigned int i = 0; i < degree; ++i)
              {
                const unsigned int n = degree + 1;
                const unsigned int a = i + n * j, b = i + 1 + n * j,
                                   c = i + 1 + n * (j + 1), d = i + n * (j + 1);
                add_cell(counter_clockwise ? Cell{{a, b, c, d}} :
                                             Cell{{a, d, c, b}});
              }
        }
    }


    template <int dim>
    template <typename CombinationOf>
    void
    ContactSurfaceMesh<dim>::add_simplex_faces(
      const fem::ElasticBody<dim>     &slave,
      const dealii::types::boundary_id boundary_id,
      const CombinationOf             &combination_of)
    {
      const dealii::FESystem<dim>       &fe        = slave.fe();
      const dealii::ReferenceCell        reference = fe.reference_cell();
      const dealii::FiniteElement<dim>  &base      = fe.base_element(0);
      const std::vector<dealii::Point<dim>> unit_points =
        base.get_unit_support_points();
      std::map<dealii::types::global_dof_index, unsigned int> point_of_dof;
      std::vector<dealii::types::global_dof_index>            cell_dofs(
        fe.n_dofs_per_cell());

      for (const auto &cell : slave.dof_handler().active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
        {
          if (cell->is_artificial() || !cell->face(f)->at_boundary() ||
              cell->face(f)->boundary_id() != boundary_id)
            continue;
          cell->get_dof_indices(cell_dofs);
          // the face's vertices (FE_SimplexP: scalar dof v at vertex v)
          // and, for P2, the dof at the midpoint of the edge of two of them
          std::vector<unsigned int> corner(dim);
          for (unsigned int v = 0; v < dim; ++v)
            corner[v] = reference.face_to_cell_vertices(f, v, 1);
          const auto dof_at = [&](const dealii::Point<dim> &xi)
          {
            for (unsigned int node = 0; node < base.n_dofs_per_cell(); ++node)
              if (unit_points[node].distance(xi) < 1e-12)
                return cell_dofs[fe.component_to_system_index(0, node)];
            Assert(false, dealii::ExcMessage("no node at a face point"));
            return dealii::types::global_dof_index(0);
          };
          const auto point_of = [&](const dealii::Point<dim> &xi)
          {
            const dealii::types::global_dof_index dof = dof_at(xi);
            const auto [it, inserted] =
              point_of_dof.emplace(dof, positions_.size());
            if (inserted)
            {
              positions_.push_back(
                slave.mapping().transform_unit_to_real_cell(cell, xi));
              combinations_.push_back(combination_of(dof));
            }
            return it->second;
          };
          // outward: from the cell's centre to the face's
          const dealii::Tensor<1, dim> outward =
            cell->face(f)->center() - cell->center();
          const auto add_cell = [&](std::vector<dealii::Point<dim>> xi)
          {
            bool carries_contact = false;
            for (const auto &x : xi)
              carries_contact = carries_contact || !combination_of(dof_at(x)).empty();
            if (!carries_contact)
              return;
            Cell points;
            for (const auto &x : xi)
              points.push_back(point_of(x));
            if constexpr (dim == 3)
            {
              const auto &a = positions_[points[0]], &b = positions_[points[1]],
                         &c = positions_[points[2]];
              if (dealii::cross_product_3d(b - a, c - a) * outward < 0)
                std::swap(points[1], points[2]);
            }
            cells_.push_back(points);
            owners_.push_back(cell->subdomain_id());
          };
          std::vector<dealii::Point<dim>> v(dim);
          for (unsigned int i = 0; i < dim; ++i)
            v[i] = reference.template vertex<dim>(corner[i]);
          const auto mid = [&](const unsigned int i, const unsigned int j)
          { return dealii::Point<dim>((v[i] + v[j]) / 2); };
          if (base.degree == 1)
            add_cell(v);
          else if constexpr (dim == 2)
          {
            add_cell({v[0], mid(0, 1)});
            add_cell({mid(0, 1), v[1]});
          }
          else
          {
            // the quadratic triangle as four linear ones
            add_cell({v[0], mid(0, 1), mid(2, 0)});
            add_cell({mid(0, 1), v[1], mid(1, 2)});
            add_cell({mid(2, 0), mid(1, 2), v[2]});
            add_cell({mid(0, 1), mid(1, 2), mid(2, 0)});
          }
        }
    }


    template <int dim>
    ContactSurfaceMesh<dim>::ContactSurfaceMesh(
      std::vector<dealii::Point<dim>> positions,
      std::vector<Combination>        combinations,
      std::vector<Cell>               cells,
      std::vector<unsigned int>       owners)
        : positions_(std::move(positions))
        , combinations_(std::move(combinations))
        , cells_(std::move(cells))
        , owners_(std::move(owners))
    {
      AssertThrow(combinations_.size() == positions_.size() &&
                    owners_.size() == cells_.size(),
                  dealii::ExcMessage("ContactSurfaceMesh: one combination "
                                     "per point and one owner per cell"));
      for (const Cell &c : cells_)
        for (const unsigned int p : c)
          AssertThrow(p < positions_.size(),
                      dealii::ExcMessage("ContactSurfaceMesh: a cell refers "
                                         "to a point that does not exist"));
    }


    template class ContactSurfaceMesh<2>;
    template class ContactSurfaceMesh<3>;
  } // namespace io
} // namespace dualcontact
