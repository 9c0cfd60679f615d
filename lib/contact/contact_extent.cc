#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <contact/contact_extent.h>
#include <util/machine.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    namespace
    {
      /**
       * The component-0 dofs of @p cell that have support on its face @p f
       * (the face's nodes), as cell-local indices.
       */
      template <int dim>
      std::vector<unsigned int>
      face_nodes(const FiniteElement<dim> &fe, const unsigned int f)
      {
        std::vector<unsigned int> local;
        for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
          if (fe.system_to_component_index(i).first == 0 &&
              fem::CellFamily<dim>::is_face_dof(fe, i, f))
            local.push_back(i);
        return local;
      }

      /**
       * Calls @p visit(cell, f, cell_dofs) for every face f of @p body on
       * @p boundary, cell_dofs being the dof indices of its cell: on a
       * distributed mesh the faces of this process' owned cells only (each
       * boundary face is one cell's, so the processes' faces partition the
       * surface; the ghost layer's would be counted twice).
       */
      template <int dim, typename Visitor>
      void
      for_each_face_on(const fem::ElasticBody<dim> &body,
                       const types::boundary_id     boundary,
                       const Visitor               &visit)
      {
        std::vector<types::global_dof_index> cell_dofs(
          body.fe().n_dofs_per_cell());
        for (const auto &cell : body.dof_handler().active_cell_iterators())
          if ((body.is_distributed() ? cell->is_locally_owned() :
                                       !cell->is_artificial()) &&
              cell->at_boundary())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  cell->face(f)->boundary_id() == boundary)
              {
                cell->get_dof_indices(cell_dofs);
                visit(cell, f, cell_dofs);
              }
      }
    } // namespace


    template <int dim>
    ContactExtent<dim>::ContactExtent(const fem::ElasticBody<dim> &slave,
                                      const types::boundary_id slave_boundary,
                                      const std::vector<Node> &nodes)
    {
      std::map<types::global_dof_index, unsigned int> index;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        index[nodes[i].dof] = i;
      // neighbours: the nodes that share a slave face
      neighbours_.assign(nodes.size(), {});
      const FiniteElement<dim> &fe = slave.fe();
      for_each_face_on(
        slave,
        slave_boundary,
        [&](const auto &,
            const unsigned int                          f,
            const std::vector<types::global_dof_index> &cell_dofs)
        {
          std::vector<unsigned int> on_face;
          for (const unsigned int i : face_nodes(fe, f))
          {
            const auto it = index.find(cell_dofs[i]);
            if (it != index.end())
              on_face.push_back(it->second);
          }
          for (const unsigned int a : on_face)
            for (const unsigned int b : on_face)
              if (a != b)
                neighbours_[a].push_back(b);
        });
      // a distributed mesh: the neighbour pairs of every process' faces
      // (the nodes are the pair's gathered ones, numbered alike on every
      // process), so that psi is the same everywhere, also at the nodes of
      // faces two cells beyond this process' ghost layer, which the far
      // neighbours reach
      if (slave.is_distributed())
      {
        std::vector<double> pairs;
        for (unsigned int a = 0; a < neighbours_.size(); ++a)
          for (const unsigned int b : neighbours_[a])
          {
            pairs.push_back(a);
            pairs.push_back(b);
          }
        const std::vector<double> all =
          util::concatenate_over_processes(pairs, slave.communicator());
        for (std::size_t k = 0; k + 1 < all.size(); k += 2)
          neighbours_[static_cast<unsigned int>(all[k])].push_back(
            static_cast<unsigned int>(all[k + 1]));
      }
      for (auto &list : neighbours_)
      {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
      }
      compute_level_function(nodes);
      integrate_zone(slave, slave_boundary, nodes);
    }


    template <int dim>
    int
    ContactExtent<dim>::far_neighbour(const std::vector<Node> &nodes,
                                      const unsigned int       c,
                                      const Tensor<1, dim>    &direction) const
    {
      // within 45 degrees of the line
      const double cos_limit = -std::sqrt(0.5);
      double       best_cos  = cos_limit;
      int          far       = -1;
      for (const unsigned int k : neighbours_[c])
        if (nodes[k].in_contact)
        {
          const Tensor<1, dim> to_k = nodes[k].position - nodes[c].position;
          const double         cos =
            to_k * direction / (to_k.norm() * direction.norm());
          if (cos < best_cos)
          {
            best_cos = cos;
            far      = k;
          }
        }
      return far;
    }


    template <int dim>
    double
    ContactExtent<dim>::extrapolate(const std::vector<Node>   &nodes,
                                    const std::vector<double> &psi,
                                    const unsigned int         inner,
                                    const unsigned int         outer,
                                    const dealii::Point<dim>  &target)
    {
      return psi[outer] +
             (psi[outer] - psi[inner]) *
               (target - nodes[outer].position).norm() /
               (nodes[outer].position - nodes[inner].position).norm();
    }


    template <int dim>
    void
    ContactExtent<dim>::compute_level_function(const std::vector<Node> &nodes)
    {
      const unsigned int  n = nodes.size();
      std::vector<double> pressure_squared(n, 0.);
      double              max_psi = 0;
      for (unsigned int i = 0; i < n; ++i)
        if (nodes[i].in_contact)
        {
          pressure_squared[i] = nodes[i].pressure * nodes[i].pressure;
          max_psi             = std::max(max_psi, pressure_squared[i]);
        }
      psi_ = pressure_squared;

      // Contact nodes beyond the edge: at a contact node c next to a
      // separated node j, p^2 extrapolated from the two contact nodes c'',
      // c' behind c on the line from j through c.  If it is negative, the
      // interior puts the edge before c: c is in contact only through the
      // force of the element that straddles the edge, lumped onto it, and
      // its p_c^2 is no value of p^2 at x_c; psi_c is then the
      // extrapolated value (the mean over c's separated neighbours).
      for (unsigned int c = 0; c < n; ++c)
        if (nodes[c].in_contact && pressure_squared[c] < max_psi)
        {
          double       sum   = 0;
          unsigned int count = 0;
          for (const unsigned int j : neighbours_[c])
            if (!nodes[j].in_contact)
            {
              const int c1 =
                far_neighbour(nodes, c, nodes[j].position - nodes[c].position);
              if (c1 < 0)
                continue;
              const int c2 =
                far_neighbour(nodes,
                              c1,
                              nodes[c].position - nodes[c1].position);
              if (c2 < 0)
                continue;
              sum +=
                extrapolate(nodes, pressure_squared, c2, c1, nodes[c].position);
              ++count;
            }
          if (count > 0 && sum < 0)
            psi_[c] = sum / count;
        }

      // separated nodes next to the zone: psi extrapolated from c' through c
      for (unsigned int j = 0; j < n; ++j)
        if (!nodes[j].in_contact)
        {
          double       sum   = 0;
          unsigned int count = 0;
          for (const unsigned int c : neighbours_[j])
            if (nodes[c].in_contact)
            {
              const int far =
                far_neighbour(nodes, c, nodes[j].position - nodes[c].position);
              sum += far >= 0 ?
                       extrapolate(nodes, psi_, far, c, nodes[j].position) :
                       -psi_[c];
              ++count;
            }
          psi_[j] =
            count > 0 ? std::min(sum / count, -1e-12 * max_psi) : -max_psi;
        }
    }


    template <int dim>
    void
    ContactExtent<dim>::integrate_zone(const fem::ElasticBody<dim> &slave,
                                       const types::boundary_id slave_boundary,
                                       const std::vector<Node> &nodes)
    {
      measure_ = 0;
      // (the nodes and so this test are the same on every process)
      if (std::none_of(nodes.begin(),
                       nodes.end(),
                       [](const Node &node) { return node.in_contact; }))
        return;
      const double max_psi = *std::max_element(psi_.begin(), psi_.end());
      std::map<types::global_dof_index, unsigned int> index;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        index[nodes[i].dof] = i;
      const AffineConstraints<double> &constraints = slave.constraints();
      // psi of a dof of the slave surface: a node's, a hanging node's from
      // its parents, anything else is no contact node (separated)
      const auto nodal_psi = [&](const types::global_dof_index dof)
      {
        const auto it = index.find(dof);
        if (it != index.end())
          return psi_[it->second];
        if (const auto *entries = constraints.get_constraint_entries(dof))
          if (!entries->empty())
          {
            double value = 0;
            for (const auto &[parent, weight] : *entries)
            {
              const auto p = index.find(parent);
              if (p == index.end())
                return -max_psi;
              value += weight * psi_[p->second];
            }
            return value;
          }
        return -max_psi;
      };

      const FiniteElement<dim> &fe = slave.fe();
      const fem::CellFamily<dim> &family = slave.cell_family();
      const Quadrature<dim - 1>   cut_rule =
        family.face_midpoint_rule(cut_face_subdivisions);
      const Quadrature<dim - 1> whole_rule =
        family.face_quadrature(fe.degree + 1);
      FEFaceValues<dim>         cut(slave.mapping(),
                            fe,
                            cut_rule,
                            update_values | update_JxW_values);
      FEFaceValues<dim>         whole(slave.mapping(),
                              fe,
                              whole_rule,
                              update_JxW_values);
      for_each_face_on(
        slave,
        slave_boundary,
        [&](const auto                                 &cell,
            const unsigned int                          f,
            const std::vector<types::global_dof_index> &cell_dofs)
        {
          const std::vector<unsigned int> local = face_nodes(fe, f);
          std::vector<double>             values;
          for (const unsigned int i : local)
            values.push_back(nodal_psi(cell_dofs[i]));
          if (std::none_of(values.begin(),
                           values.end(),
                           [](const double v) { return v > 0; }))
            return;
          if (std::all_of(values.begin(),
                          values.end(),
                          [](const double v) { return v >= 0; }))
          {
            whole.reinit(cell, f);
            for (const unsigned int q : whole.quadrature_point_indices())
              measure_ += whole.JxW(q);
            return;
          }
          cut.reinit(cell, f);
          for (const unsigned int q : cut.quadrature_point_indices())
          {
            double psi_h = 0;
            for (unsigned int k = 0; k < local.size(); ++k)
              psi_h += values[k] * cut.shape_value(local[k], q);
            if (psi_h > 0)
              measure_ += cut.JxW(q);
          }
        });
      // this process' faces are its share of the zone (collective)
      if (slave.is_distributed())
        measure_ = Utilities::MPI::sum(measure_, slave.communicator());
    }


    template class ContactExtent<2>;
    template class ContactExtent<3>;
  } // namespace contact
} // namespace dualcontact
