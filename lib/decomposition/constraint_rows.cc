#include <deal.II/base/exceptions.h>

#include <decomposition/constraint_rows.h>

#include <cmath>

namespace dualcontact
{
  namespace decomposition
  {
    template <int dim>
    ConstraintRows<dim>::ConstraintRows(
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const contact::ContactDiscretization<dim>        &contact,
      const std::vector<unsigned int>                  &frictional_nodes,
      const Layout                                     &layout,
      const Gluing                                      gluing)
        : bodies_(bodies)
        , kept_here_(layout.kept_here)
        , entries_(layout.dofs.size())
    {
      add_contact_rows(contact, frictional_nodes, layout);

      // the copies of every dof of a body, in subdomain order
      std::vector<
        std::vector<std::vector<std::pair<unsigned int, unsigned int>>>>
        copies(bodies_.size());
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        copies[b].resize(bodies_[b]->n_dofs());
        for (unsigned int s = layout.first_subdomain[b];
             s < layout.first_subdomain[b + 1];
             ++s)
          for (unsigned int l = 0; l < layout.dofs[s].size(); ++l)
            copies[b][layout.dofs[s][l]].push_back({s, l});
      }
      add_gluing_rows(copies, layout, gluing);
      add_dirichlet_rows(copies);
    }


    template <int dim>
    void
    ConstraintRows<dim>::add_contact_rows(
      const contact::ContactDiscretization<dim> &contact,
      const std::vector<unsigned int>           &frictional_nodes,
      const Layout                              &layout)
    {
      // the body dofs of ContactDiscretization's columns (stacked over the
      // bodies) mapped to their first copy
      const auto add_contact_row = [&](const dealii::SparseMatrix<double> &B,
                                       const unsigned int source,
                                       const double       c)
      {
        const unsigned int row = add_row(c);
        for (auto it = B.begin(source); it != B.end(source); ++it)
        {
          if (it->value() == 0.)
            continue;
          const unsigned int b = contact.body_of_dof(it->column());
          const auto [s, l] =
            layout.first_copy[b][it->column() - contact.body_offset(b)];
          add_entry(s, row, l, it->value());
        }
      };
      const dealii::Vector<double> &gap = contact.normal_bound();
      for (unsigned int i = 0; i < contact.n_nodes(); ++i)
        add_contact_row(contact.normal_matrix(), i, gap(i));
      for (const unsigned int node : frictional_nodes)
        for (unsigned int k = 0; k + 1 < dim; ++k)
        {
          const unsigned int source = (dim - 1) * node + k;
          add_contact_row(contact.tangential_matrix(),
                          source,
                          -contact.tangential_offset()(source));
        }
    }


    template <int dim>
    bool
    ConstraintRows<dim>::prescribed(const unsigned int b,
                                    const unsigned int i) const
    {
      return bodies_[b]->constraints().is_constrained(i) &&
             !bodies_[b]->hanging_node_constraints().is_constrained(i);
    }


    template <int dim>
    void
    ConstraintRows<dim>::add_gluing_rows(
      const std::vector<
        std::vector<std::vector<std::pair<unsigned int, unsigned int>>>>
                   &copies,
      const Layout &layout,
      const Gluing  gluing)
    {
      // the copies of every dof that is not prescribed (hanging dofs too)
      for (unsigned int b = 0; b < bodies_.size(); ++b)
        for (unsigned int i = 0; i < copies[b].size(); ++i)
          if (!prescribed(b, i))
            add_copy_rows(copies[b][i], gluing);
      // hanging-node rows, counted with the gluing rows (see the class
      // documentation for why rows)
      for (unsigned int b = 0; b < bodies_.size(); ++b)
        for (const auto &line :
             bodies_[b]->hanging_node_constraints().get_lines())
        {
          const unsigned int row = add_row(0.);
          const auto [s, l]      = layout.first_copy[b][line.index];
          add_entry(s, row, l, 1.);
          for (const auto &[parent, weight] : line.entries)
          {
            const auto [sp, lp] = layout.first_copy[b][parent];
            add_entry(sp, row, lp, -weight);
          }
          ++n_gluing_;
        }
    }


    template <int dim>
    void
    ConstraintRows<dim>::add_copy_rows(
      const std::vector<std::pair<unsigned int, unsigned int>> &copies,
      const Gluing                                              gluing)
    {
      for (unsigned int j = 1; j < copies.size(); ++j)
      {
        const unsigned int row = add_row(0.);
        if (gluing == Gluing::chain)
        {
          add_entry(copies[j - 1].first, row, copies[j - 1].second, 1.);
          add_entry(copies[j].first, row, copies[j].second, -1.);
        }
        else
        {
          // Helmert's row j: orthogonal to the rows before it and to
          // (1, ..., 1), the glued motion, and of unit norm
          const double scale = 1. / std::sqrt(j * (j + 1.));
          for (unsigned int i = 0; i < j; ++i)
            add_entry(copies[i].first, row, copies[i].second, scale);
          add_entry(copies[j].first, row, copies[j].second, -(j * scale));
        }
        ++n_gluing_;
      }
    }


    template <int dim>
    void
    ConstraintRows<dim>::add_dirichlet_rows(
      const std::vector<
        std::vector<std::vector<std::pair<unsigned int, unsigned int>>>>
        &copies)
    {
      // every copy of a prescribed dof
      for (unsigned int b = 0; b < bodies_.size(); ++b)
        for (unsigned int i = 0; i < copies[b].size(); ++i)
          if (prescribed(b, i))
            for (const auto &[s, l] : copies[b][i])
            {
              const unsigned int row =
                add_row(bodies_[b]->constraints().get_inhomogeneity(i));
              add_entry(s, row, l, 1.);
              dirichlet_rows_.push_back({row, b, i});
              ++n_dirichlet_;
            }
    }


    template <int dim>
    unsigned int
    ConstraintRows<dim>::add_row(const double c)
    {
      c_.push_back(c);
      return c_.size() - 1;
    }


    template <int dim>
    void
    ConstraintRows<dim>::add_entry(const unsigned int s,
                                   const unsigned int row,
                                   const unsigned int local,
                                   const double       value)
    {
      if (kept_here_[s])
        entries_[s].push_back({row, local, value});
    }


    template <int dim>
    unsigned int
    ConstraintRows<dim>::n_rows() const
    {
      return c_.size();
    }


    template <int dim>
    unsigned int
    ConstraintRows<dim>::n_gluing() const
    {
      return n_gluing_;
    }


    template <int dim>
    unsigned int
    ConstraintRows<dim>::n_dirichlet() const
    {
      return n_dirichlet_;
    }


    template <int dim>
    double
    ConstraintRows<dim>::rhs(const unsigned int r) const
    {
      AssertIndexRange(r, c_.size());
      return c_[r];
    }


    template <int dim>
    void
    ConstraintRows<dim>::update_rhs(
      const contact::ContactDiscretization<dim> &contact,
      const std::vector<unsigned int>           &frictional_nodes)
    {
      // the contact rows come first, in add_contact_rows()' order
      const dealii::Vector<double> &gap = contact.normal_bound();
      unsigned int                  row = 0;
      for (unsigned int i = 0; i < contact.n_nodes(); ++i)
        c_[row++] = gap(i);
      for (const unsigned int node : frictional_nodes)
        for (unsigned int k = 0; k + 1 < dim; ++k)
          c_[row++] = -contact.tangential_offset()((dim - 1) * node + k);
      for (const DirichletRow &r : dirichlet_rows_)
        c_[r.row] = bodies_[r.body]->constraints().get_inhomogeneity(r.dof);
    }


    template <int dim>
    const std::vector<typename ConstraintRows<dim>::Entry> &
    ConstraintRows<dim>::entries(const unsigned int s) const
    {
      AssertIndexRange(s, entries_.size());
      return entries_[s];
    }


    template class ConstraintRows<2>;
    template class ConstraintRows<3>;
  } // namespace decomposition
} // namespace dualcontact
