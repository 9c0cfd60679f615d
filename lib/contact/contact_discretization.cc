#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <contact/contact_discretization.h>
#include <contact/master_surface.h>
#include <contact/mortar_coupling.h>
#include <contact/node_to_segment.h>
#include <contact/row_entries.h>
#include <util/machine.h>

#include <algorithm>
#include <limits>
#include <map>
#include <memory>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    namespace
    {
      /** Unit tangents completing n to an orthonormal frame. */
      template <int dim>
      std::array<Tensor<1, dim>, dim - 1>
      make_tangents(const Tensor<1, dim> &n, const Tensor<1, dim> &hint)
      {
        std::array<Tensor<1, dim>, dim - 1> t;
        if constexpr (dim == 2)
        {
          t[0][0] = -n[1];
          t[0][1] = n[0];
        }
        else
        {
          Tensor<1, dim> a = hint - (hint * n) * n;
          if (a.norm() < 1e-3 * std::max(hint.norm(), 1e-300))
          {
            // the coordinate axis least aligned with n
            unsigned int axis = 0;
            for (unsigned int d = 1; d < dim; ++d)
              if (std::abs(n[d]) < std::abs(n[axis]))
                axis = d;
            Tensor<1, dim> e;
            e[axis] = 1;
            a       = e - (e * n) * n;
          }
          t[0] = a / a.norm();
          t[1] = cross_product_3d(n, t[0]);
        }
        return t;
      }

      /** A slave node before it is placed: its dofs, its weight int phi
       * ds and its weighted normal int phi n ds. */
      template <int dim>
      struct SlaveNode
      {
        std::array<types::global_dof_index, dim> dofs;
        double                                   weight = 0;
        Tensor<1, dim>                           normal;
      };


      /** The slave side of a pair: its nodes by key (the node's
       * first-component dof) and, per slave face, the weights int_f phi ds
       * of the face's nodes. */
      template <int dim>
      struct SlaveSide
      {
        std::map<types::global_dof_index, SlaveNode<dim>>      nodes;
        std::vector<std::map<types::global_dof_index, double>> face_weights;
      };


      /** Throws unless the pair names two different existing bodies (or a
       * body and an obstacle). */
      template <int dim>
      void
      check_pair(const ContactPair<dim> &pair, const unsigned int n_bodies)
      {
        AssertThrow(pair.slave_body < n_bodies &&
                      (pair.obstacle || pair.master_body < n_bodies),
                    ExcMessage("Contact pair `" + pair.name +
                               "' names a body that does not exist."));
        AssertThrow(pair.obstacle || pair.master_body != pair.slave_body,
                    ExcMessage("Contact pair `" + pair.name +
                               "': self-contact is not supported."));
      }


      /** The nodes of the slave boundary with their weights and weighted
       * normals, integrated face by face. */
      template <int dim>
      SlaveSide<dim>
      integrate_slave_side(const ContactPair<dim>      &pair,
                           const fem::ElasticBody<dim> &slave)
      {
        const FiniteElement<dim>            &fe = slave.fe();
        SlaveSide<dim>                       side;
        const Quadrature<dim - 1>            quadrature =
          slave.cell_family().face_quadrature(fe.degree + 1);
        FEFaceValues<dim>                    fe_face(slave.mapping(),
                                  fe,
                                  quadrature,
                                  update_values | update_normal_vectors |
                                    update_JxW_values);
        std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
        for (const auto &cell : slave.dof_handler().active_cell_iterators())
          for (const unsigned int f : cell->face_indices())
            if ((!slave.is_distributed() || cell->is_locally_owned()) &&
                cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == pair.slave_boundary)
            {
              fe_face.reinit(cell, f);
              cell->get_dof_indices(cell_dofs);
              side.face_weights.emplace_back();
              for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
                if (fe.system_to_component_index(k).first == 0 &&
                    fem::CellFamily<dim>::is_face_dof(fe, k, f))
                {
                  const unsigned int node =
                    fe.system_to_component_index(k).second;
                  SlaveNode<dim> &a = side.nodes[cell_dofs[k]];
                  for (unsigned int c = 0; c < dim; ++c)
                    a.dofs[c] =
                      cell_dofs[fe.component_to_system_index(c, node)];
                  for (unsigned int q = 0; q < quadrature.size(); ++q)
                  {
                    const double w =
                      fem::CellFamily<dim>::lumping_function(fe_face, k, q) *
                      fe_face.JxW(q);
                    a.weight += w;
                    side.face_weights.back()[cell_dofs[k]] += w;
                    a.normal += w * fe_face.normal_vector(q);
                  }
                }
            }
        // on a distributed mesh a process may hold none of the faces:
        // decided on the gathered side (gather_slave_side())
        AssertThrow(slave.is_distributed() || !side.face_weights.empty(),
                    ExcMessage("Contact pair `" + pair.name +
                               "': the slave body `" + slave.name() +
                               "' has no boundary with id " +
                               std::to_string(pair.slave_boundary) + "."));
        return side;
      }


      /**
       * The slave side of a pair on a distributed mesh, from every
       * process' part (integrate_slave_side() of its own cells): the nodes
       * by key with their weights and weighted normals summed over the
       * processes that share them, the faces of all processes (in process
       * order), and the support point of every node.  What is gathered is
       * the slave surface, not the mesh.  Collective.
       */
      template <int dim>
      std::map<types::global_dof_index, Point<dim>>
      gather_slave_side(const ContactPair<dim>      &pair,
                        const fem::ElasticBody<dim> &slave,
                        SlaveSide<dim>              &side)
      {
        std::map<types::global_dof_index, Point<dim>> points;
        DoFTools::map_dofs_to_support_points(slave.mapping(),
                                             slave.dof_handler(),
                                             points);
        // self-delimiting records: nodes (key, dofs, weight, normal,
        // position), then faces ((key, weight) pairs)
        std::vector<double> local;
        local.push_back(side.nodes.size());
        for (const auto &[key, node] : side.nodes)
        {
          local.push_back(key);
          local.insert(local.end(), node.dofs.begin(), node.dofs.end());
          local.push_back(node.weight);
          for (unsigned int d = 0; d < dim; ++d)
            local.push_back(node.normal[d]);
          for (unsigned int d = 0; d < dim; ++d)
            local.push_back(points.at(key)[d]);
        }
        local.push_back(side.face_weights.size());
        for (const auto &face : side.face_weights)
        {
          local.push_back(face.size());
          for (const auto &[key, w] : face)
          {
            local.push_back(key);
            local.push_back(w);
          }
        }
        const std::vector<double> all =
          util::concatenate_over_processes(local, slave.communicator());

        SlaveSide<dim>                                merged;
        std::map<types::global_dof_index, Point<dim>> positions;
        const auto as_dof = [](const double x)
        { return static_cast<types::global_dof_index>(x); };
        for (std::size_t i = 0; i < all.size();)
        {
          const std::size_t n_nodes = all[i++];
          for (std::size_t n = 0; n < n_nodes; ++n)
          {
            const types::global_dof_index key  = as_dof(all[i++]);
            SlaveNode<dim>               &node = merged.nodes[key];
            for (unsigned int c = 0; c < dim; ++c)
              node.dofs[c] = as_dof(all[i++]);
            node.weight += all[i++];
            for (unsigned int d = 0; d < dim; ++d)
              node.normal[d] += all[i++];
            Point<dim> &x = positions[key];
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = all[i++];
          }
          const std::size_t n_faces = all[i++];
          for (std::size_t f = 0; f < n_faces; ++f)
          {
            merged.face_weights.emplace_back();
            const std::size_t n_entries = all[i++];
            for (std::size_t e = 0; e < n_entries; ++e, i += 2)
              merged.face_weights.back()[as_dof(all[i])] += all[i + 1];
          }
        }
        AssertThrow(!merged.face_weights.empty(),
                    ExcMessage("Contact pair `" + pair.name +
                               "': the slave body `" + slave.name() +
                               "' has no boundary with id " +
                               std::to_string(pair.slave_boundary) + "."));
        side = std::move(merged);
        return positions;
      }


      /**
       * Hanging slave nodes (3D: the midpoint of a coarse face's edge next
       * to refined faces) are no contact nodes.  Their displacement is the
       * constraint's combination of the parent nodes', so their
       * non-penetration rows would (nearly) repeat the parents' and make F
       * singular, with the multipliers split arbitrarily between them.  The
       * fine shape function phi_h of such a node is part of the parents'
       * basis functions (phi_j + c_j phi_h on the refined side), so its
       * weight and weighted normal go to the parents with the constraint's
       * coefficients: w_j = int (phi_j + c_j phi_h) ds.
       */
      template <int dim>
      void
      move_hanging_nodes_to_parents(const fem::ElasticBody<dim> &slave,
                                    SlaveSide<dim>              &side)
      {
        const AffineConstraints<double> &hanging =
          slave.hanging_node_constraints();
        // the faces of every hanging node, so that moving a node's weights
        // visits its own faces, not all of them (parents are never hanging,
        // so the lists stay valid while weights move)
        std::map<types::global_dof_index, std::vector<unsigned int>>
          faces_of_hanging_node;
        for (unsigned int f = 0; f < side.face_weights.size(); ++f)
          for (const auto &[key, w] : side.face_weights[f])
            if (hanging.is_constrained(key))
              faces_of_hanging_node[key].push_back(f);
        for (auto it = side.nodes.begin(); it != side.nodes.end();)
        {
          if (!hanging.is_constrained(it->first))
          {
            ++it;
            continue;
          }
          const auto *line = hanging.get_constraint_entries(it->first);
          Assert(line != nullptr, ExcInternalError());
          for (const unsigned int f : faces_of_hanging_node[it->first])
          {
            auto      &face = side.face_weights[f];
            const auto h    = face.find(it->first);
            Assert(h != face.end(), ExcInternalError());
            const double w = h->second;
            face.erase(h);
            for (const auto &[parent, coefficient] : *line)
              face[parent] += coefficient * w;
          }
          for (const auto &[parent, coefficient] : *line)
          {
            const auto to = side.nodes.find(parent);
            // the parents are the vertices of the coarse face's edge:
            // slave boundary nodes themselves, never hanging (closed)
            Assert(to != side.nodes.end(), ExcInternalError());
            to->second.weight += coefficient * it->second.weight;
            to->second.normal += coefficient * it->second.normal;
          }
          it = side.nodes.erase(it);
        }
      }


      /** The row of B for the relative displacement of @p node along
       * @p direction: slave minus master. */
      template <int dim>
      std::vector<RowEntry>
      make_row(const ContactNode<dim> &node,
               const MasterEntries    &master,
               const Tensor<1, dim>   &direction)
      {
        std::vector<RowEntry> row;
        for (unsigned int c = 0; c < dim; ++c)
          if (direction[c] != 0.)
            row.push_back({node.body, node.dofs[c], master.own * direction[c]});
        for (unsigned int e = 0; e < master.entries.size(); ++e)
          if (direction[master.components[e]] != 0.)
            row.push_back(
              {master.entries[e].body,
               master.entries[e].dof,
               -master.entries[e].value * direction[master.components[e]]});
        return row;
      }


      /** Rows of B as a sparse matrix (columns: the bodies' dofs one after
       * the other, from @p offsets). */
      void
      make_matrix(
        const std::vector<std::map<types::global_dof_index, double>> &rows,
        const types::global_dof_index                                 n_columns,
        SparsityPattern                                              &pattern,
        SparseMatrix<double>                                         &matrix)
      {
        DynamicSparsityPattern dsp(rows.size(), n_columns);
        for (unsigned int r = 0; r < rows.size(); ++r)
          for (const auto &[column, value] : rows[r])
            dsp.add(r, column);
        pattern.copy_from(dsp);
        matrix.reinit(pattern);
        for (unsigned int r = 0; r < rows.size(); ++r)
          for (const auto &[column, value] : rows[r])
            matrix.set(r, column, value);
      }


      /** @p rows on the stacked dofs of all bodies, as they are
       * (unconstrained): the coupling whose transpose gives the nodal
       * contact forces. */
      void
      stack_rows(const std::vector<std::vector<RowEntry>>   &rows,
                 const std::vector<types::global_dof_index> &offsets,
                 SparsityPattern                            &pattern,
                 SparseMatrix<double>                       &matrix)
      {
        std::vector<std::map<types::global_dof_index, double>> stacked(
          rows.size());
        for (unsigned int r = 0; r < rows.size(); ++r)
          for (const RowEntry &entry : rows[r])
            stacked[r][offsets[entry.body] + entry.dof] += entry.value;
        make_matrix(stacked, offsets.back(), pattern, matrix);
      }


      /** Condenses @p rows through the bodies' constraints into @p matrix
       * (columns: the bodies' dofs one after the other, from @p offsets)
       * and the rows' inhomogeneities into @p offset. */
      template <int dim>
      void
      condense_rows(const std::vector<std::vector<RowEntry>>         &rows,
                    const std::vector<const fem::ElasticBody<dim> *> &bodies,
                    const std::vector<types::global_dof_index>       &offsets,
                    SparsityPattern                                  &pattern,
                    SparseMatrix<double>                             &matrix,
                    Vector<double>                                   &offset)
      {
        std::vector<std::map<types::global_dof_index, double>> condensed(
          rows.size());
        offset.reinit(rows.size());
        for (unsigned int r = 0; r < rows.size(); ++r)
          for (const RowEntry &entry : rows[r])
          {
            const AffineConstraints<double> &constraints =
              bodies[entry.body]->constraints();
            const types::global_dof_index offset_b = offsets[entry.body];
            if (constraints.is_constrained(entry.dof))
            {
              offset(r) +=
                entry.value * constraints.get_inhomogeneity(entry.dof);
              if (const auto *line =
                    constraints.get_constraint_entries(entry.dof))
                for (const auto &[dof, weight] : *line)
                  condensed[r][offset_b + dof] += entry.value * weight;
            }
            else
              condensed[r][offset_b + entry.dof] += entry.value;
          }
        make_matrix(condensed, offsets.back(), pattern, matrix);
      }


      /**
       * The normal of a slave node on a symmetry plane: a component of the
       * node's displacement prescribed (a roller, u_c given) while another
       * is free.  The support takes every force along e_c, so a contact
       * force with a component along it would be carried by the support:
       * on a half or quarter model the nodal normal from the faces on one
       * side of the plane (the master facet's normal, or the average of
       * the slave faces around the node) tilts out of the plane and the
       * symmetry reactions of a frictionless contact become nonzero, where
       * the whole body has its normal in the plane.  Projected on the
       * plane(s), the normal is the mirror-symmetric one.  A node with all
       * components prescribed keeps its normal (nothing to mirror).
       */
      template <int dim>
      Tensor<1, dim>
      symmetric_normal(const Tensor<1, dim>                           &normal,
                       const std::array<types::global_dof_index, dim> &dofs,
                       const AffineConstraints<double> &constraints)
      {
        Tensor<1, dim> projected    = normal;
        unsigned int   n_prescribed = 0;
        for (unsigned int c = 0; c < dim; ++c)
          if (const auto *line = constraints.get_constraint_entries(dofs[c]);
              line != nullptr && line->empty())
          {
            projected[c] = 0;
            ++n_prescribed;
          }
        if (n_prescribed == 0 || n_prescribed == dim ||
            projected.norm() < 1e-3 * normal.norm())
          return normal;
        return projected / projected.norm();
      }
    } // namespace


    template <int dim>
    ContactDiscretization<dim>::ContactDiscretization(
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const std::vector<ContactPair<dim>>              &pairs)
        : pairs_(pairs)
    {
      offsets_.resize(bodies.size() + 1, 0);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        offsets_[b + 1] = offsets_[b] + bodies[b]->n_dofs();

      std::vector<std::vector<RowEntry>> rows_n, rows_t;
      for (unsigned int p = 0; p < pairs_.size(); ++p)
      {
        const ContactPair<dim> &pair = pairs_[p];
        check_pair(pair, bodies.size());
        const fem::ElasticBody<dim> &slave = *bodies[pair.slave_body];
        SlaveSide<dim>               side  = integrate_slave_side(pair, slave);
        // the support points of the slave nodes
        std::vector<Point<dim>> support_points(slave.n_dofs());
        if (slave.is_distributed())
        {
          for (const auto &[key, x] : gather_slave_side(pair, slave, side))
            support_points[key] = x;
        }
        else
          DoFTools::map_dofs_to_support_points(slave.mapping(),
                                               slave.dof_handler(),
                                               support_points);
        // on the gathered side of a distributed mesh too (the hanging
        // lines are every process')
        move_hanging_nodes_to_parents(slave, side);
        const std::unique_ptr<MasterSurface<dim>> master_surface =
          pair.obstacle ?
            nullptr :
            std::make_unique<MasterSurface<dim>>(*bodies[pair.master_body],
                                                 pair.master_boundary,
                                                 pair.name);

        // per node: master point, frame, gap, rows
        PairSummary summary;
        summary.name    = pair.name;
        summary.min_gap = std::numeric_limits<double>::max();
        summary.max_gap = -std::numeric_limits<double>::max();
        std::map<types::global_dof_index, unsigned int> node_of_key;
        const bool                                      mortar =
          pair.discretization == ContactPair<dim>::Discretization::mortar;
        // one placement of the nodes per discretization
        std::unique_ptr<MortarCoupling<dim>> coupling;
        std::unique_ptr<NodeToSegment<dim>>  node_to_segment;
        if (mortar)
          coupling =
            std::make_unique<MortarCoupling<dim>>(pair,
                                                  slave,
                                                  pair.obstacle ?
                                                    nullptr :
                                                    bodies[pair.master_body],
                                                  master_surface.get());
        else
        {
          std::vector<Point<dim>> positions;
          for (const auto &entry : side.nodes)
            positions.push_back(support_points[entry.first]);
          node_to_segment = std::make_unique<NodeToSegment<dim>>(
            pair, bodies, master_surface.get(), positions);
        }
        unsigned int index = 0;
        for (const auto &[key, a] : side.nodes)
        {
          const unsigned int i = index++;
          ContactNode<dim>   node;
          node.pair     = p;
          node.body     = pair.slave_body;
          node.dofs     = a.dofs;
          node.position = support_points[key];
          node.weight   = a.weight;
          MasterEntries master;
          if (mortar ? !coupling->place(key, a.normal, node, master) :
                       !node_to_segment->place(i, node, master))
            continue;
          // an obstacle's normal is exact; a master facet's is one side's
          if (!pair.obstacle)
            node.normal = symmetric_normal<dim>(node.normal,
                                                node.dofs,
                                                slave.constraints());
          node.tangents =
            make_tangents<dim>(node.normal, pair.first_tangent_direction);
          if (mortar)
          {
            node.gap          = coupling->gap(key, node.normal);
            node.master_point = node.position + node.gap * node.normal;
          }
          else
            node.gap = (node.master_point - node.position) * node.normal;
          rows_n.push_back(make_row(node, master, node.normal));
          for (unsigned int k = 0; k + 1 < dim; ++k)
            rows_t.push_back(make_row(node, master, node.tangents[k]));

          ++summary.n_nodes;
          summary.min_gap = std::min(summary.min_gap, node.gap);
          summary.max_gap = std::max(summary.max_gap, node.gap);
          summary.area += node.weight;
          node_of_key[key] = nodes_.size();
          nodes_.push_back(node);
        }
        add_faces(p, side.face_weights, node_of_key);
        AssertThrow(summary.n_nodes > 0,
                    ExcMessage("Contact pair `" + pair.name +
                               "': no slave node found the master within "
                               "the search distance " +
                               std::to_string(pair.search_distance) + " m."));
        summaries_.push_back(summary);
      }

      condense_rows(rows_n,
                    bodies,
                    offsets_,
                    normal_pattern_,
                    normal_matrix_,
                    normal_offset_);
      condense_rows(rows_t,
                    bodies,
                    offsets_,
                    tangential_pattern_,
                    tangential_matrix_,
                    tangential_offset_);
      stack_rows(rows_n, offsets_, full_normal_pattern_, full_normal_matrix_);
      stack_rows(rows_t,
                 offsets_,
                 full_tangential_pattern_,
                 full_tangential_matrix_);
      gaps_.reinit(nodes_.size());
      for (unsigned int i = 0; i < nodes_.size(); ++i)
        gaps_(i) = nodes_[i].gap;
    }


    template <int dim>
    void
    ContactDiscretization<dim>::update_offsets(
      const std::vector<const fem::ElasticBody<dim> *> &bodies)
    {
      AssertDimension(bodies.size() + 1, offsets_.size());
      // B_full applied to the prescribed values (the inhomogeneities, zero
      // at free dofs) is what condense_rows() sums into the offsets
      Vector<double> prescribed(n_dofs());
      for (unsigned int b = 0; b < bodies.size(); ++b)
        for (const auto &line : bodies[b]->constraints().get_lines())
          prescribed(offsets_[b] + line.index) = line.inhomogeneity;
      full_normal_matrix_.vmult(normal_offset_, prescribed);
      full_tangential_matrix_.vmult(tangential_offset_, prescribed);
    }


    template <int dim>
    Vector<double>
    ContactDiscretization<dim>::nodal_contact_forces(
      const Vector<double> &normal_multipliers,
      const Vector<double> &tangential_multipliers) const
    {
      AssertDimension(normal_multipliers.size(), n_nodes());
      AssertDimension(tangential_multipliers.size(), (dim - 1) * n_nodes());
      Vector<double> forces(n_dofs());
      full_normal_matrix_.Tvmult(forces, normal_multipliers);
      full_tangential_matrix_.Tvmult_add(forces, tangential_multipliers);
      forces *= -1.;
      return forces;
    }


    template <int dim>
    void
    ContactDiscretization<dim>::add_faces(
      const unsigned int pair,
      const std::vector<std::map<types::global_dof_index, double>>
                                                            &face_weights,
      const std::map<types::global_dof_index, unsigned int> &node_of_key)
    {
      for (const auto &face : face_weights)
      {
        ContactFace contact_face;
        contact_face.pair = pair;
        for (const auto &[key, w] : face)
        {
          const auto n = node_of_key.find(key);
          if (n != node_of_key.end())
            contact_face.nodes.emplace_back(n->second, w);
        }
        if (!contact_face.nodes.empty())
          faces_.push_back(contact_face);
      }
    }


    template <int dim>
    unsigned int
    ContactDiscretization<dim>::n_nodes() const
    {
      return nodes_.size();
    }

    template <int dim>
    const std::vector<ContactNode<dim>> &
    ContactDiscretization<dim>::nodes() const
    {
      return nodes_;
    }

    template <int dim>
    const std::vector<typename ContactDiscretization<dim>::PairSummary> &
    ContactDiscretization<dim>::pair_summaries() const
    {
      return summaries_;
    }


    template <int dim>
    const std::vector<ContactFace> &
    ContactDiscretization<dim>::faces() const
    {
      return faces_;
    }

    template <int dim>
    const std::vector<ContactPair<dim>> &
    ContactDiscretization<dim>::pairs() const
    {
      return pairs_;
    }

    template <int dim>
    types::global_dof_index
    ContactDiscretization<dim>::n_dofs() const
    {
      return offsets_.back();
    }

    template <int dim>
    types::global_dof_index
    ContactDiscretization<dim>::body_offset(const unsigned int body) const
    {
      return offsets_.at(body);
    }

    template <int dim>
    unsigned int
    ContactDiscretization<dim>::body_of_dof(
      const types::global_dof_index dof) const
    {
      AssertIndexRange(dof, n_dofs());
      return std::upper_bound(offsets_.begin(), offsets_.end(), dof) -
             offsets_.begin() - 1;
    }

    template <int dim>
    const SparseMatrix<double> &
    ContactDiscretization<dim>::normal_matrix() const
    {
      return normal_matrix_;
    }

    template <int dim>
    const SparseMatrix<double> &
    ContactDiscretization<dim>::tangential_matrix() const
    {
      return tangential_matrix_;
    }

    template <int dim>
    const Vector<double> &
    ContactDiscretization<dim>::gaps() const
    {
      return gaps_;
    }

    template <int dim>
    const Vector<double> &
    ContactDiscretization<dim>::normal_offset() const
    {
      return normal_offset_;
    }

    template <int dim>
    const Vector<double> &
    ContactDiscretization<dim>::tangential_offset() const
    {
      return tangential_offset_;
    }

    template <int dim>
    Vector<double>
    ContactDiscretization<dim>::normal_bound() const
    {
      Vector<double> bound = gaps_;
      bound -= normal_offset_;
      return bound;
    }


    template class ContactDiscretization<2>;
    template class ContactDiscretization<3>;
  } // namespace contact
} // namespace dualcontact
