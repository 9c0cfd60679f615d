#pragma once

#include <deal.II/base/types.h>

#include <contact/contact_discretization.h>
#include <decomposition/decomposition_parameters.h>
#include <fem/elastic_body.h>

#include <utility>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * The rows of TFETI's B u = c in the subdomains' numbering, in the
     * multipliers' order: contact rows (normal, then tangential of the
     * frictional nodes, as ContactDiscretization numbers them), gluing rows
     * (with the hanging-node rows), Dirichlet rows.
     *
     * - Contact: a row of ContactDiscretization's B_N / B_T, its body dofs
     *   mapped to their first copy.
     * - Gluing: a chain u_s(i) - u_t(i) = 0 through the copies of every dof
     *   that is not prescribed (redundancy-free, not orthonormalized).
     * - Hanging nodes: u_h - sum_j w_j u_j = 0 between first copies.  As
     *   rows, not condensed into K_s: every cell keeps its own
     *   (isoparametric) vertices, so the rigid motions stay in the kernel
     *   of K_s even where a refined vertex lies on a curved manifold off
     *   the coarse edge (there the condensed K_s has no exact rotation).
     * - Dirichlet: u_s(i) = g_i for every copy of a prescribed dof
     *   (constrained and not hanging: a hanging dof whose parents are all
     *   prescribed has a constraint line without entries too).
     *
     * The rows are numbered alike on every process; only the owner of a
     * subdomain keeps the entries of its B_s.
     */
    template <int dim>
    class ConstraintRows
    {
    public:
      /** An entry of B_s: row, local dof of the subdomain, value. */
      struct Entry
      {
        unsigned int row;
        unsigned int local;
        double       value;
      };

      /** Where the bodies' dofs went (TFETIDual's decomposition). */
      struct Layout
      {
        /** Per subdomain (on every process): its body dofs. */
        const std::vector<std::vector<dealii::types::global_dof_index>> &dofs;
        /** The subdomains of body b: first_subdomain[b] .. [b + 1] - 1. */
        const std::vector<unsigned int> &first_subdomain;
        /** Per body dof, its copy in the lowest subdomain (s, local). */
        const std::vector<std::vector<std::pair<unsigned int, unsigned int>>>
          &first_copy;
        /** Per subdomain, whether this process keeps its entries. */
        const std::vector<bool> &kept_here;
      };
      using Gluing = DecompositionParameters::Gluing;

      ConstraintRows(const std::vector<const fem::ElasticBody<dim> *> &bodies,
                     const contact::ContactDiscretization<dim>        &contact,
                     const std::vector<unsigned int> &frictional_nodes,
                     const Layout                    &layout,
                     const Gluing                     gluing);

      /** All rows: contact, gluing (with hanging-node), Dirichlet. */
      unsigned int
      n_rows() const;
      unsigned int
      n_gluing() const;
      unsigned int
      n_dirichlet() const;
      /** The right-hand side c_r of row @p r [m]. */
      double
      rhs(const unsigned int r) const;
      /**
       * The right-hand sides of a new load step: the contact rows' from
       * @p contact's gaps and offsets (ContactDiscretization::
       * update_offsets()), the Dirichlet rows' from the bodies' prescribed
       * values at the new time (fem::ElasticBody::set_load_time()); the
       * entries of B and the gluing rows (c = 0) stay.  @p frictional_nodes
       * as given to the constructor.
       */
      void
      update_rhs(const contact::ContactDiscretization<dim> &contact,
                 const std::vector<unsigned int>           &frictional_nodes);
      /** The entries of B_s (empty unless kept here). */
      const std::vector<Entry> &
      entries(const unsigned int s) const;

    private:
      void
      add_contact_rows(const contact::ContactDiscretization<dim> &contact,
                       const std::vector<unsigned int> &frictional_nodes,
                       const Layout                    &layout);
      /** Gluing rows through the copies, then the hanging-node rows. */
      void
      add_gluing_rows(
        const std::vector<
          std::vector<std::vector<std::pair<unsigned int, unsigned int>>>>
                     &copies,
        const Layout &layout,
        const Gluing  gluing);
      /** The k - 1 rows gluing the k copies (subdomain, local dof) of one
       *  dof. */
      void
      add_copy_rows(
        const std::vector<std::pair<unsigned int, unsigned int>> &copies,
        const Gluing                                              gluing);
      void
      add_dirichlet_rows(
        const std::vector<
          std::vector<std::vector<std::pair<unsigned int, unsigned int>>>>
          &copies);
      /** Whether dof @p i of body @p b is under a Dirichlet condition. */
      bool
      prescribed(const unsigned int b, const unsigned int i) const;

      /** Adds a row of B; returns its index. */
      unsigned int
      add_row(const double c);
      void
      add_entry(const unsigned int s,
                const unsigned int row,
                const unsigned int local,
                const double       value);

      std::vector<const fem::ElasticBody<dim> *> bodies_;
      std::vector<bool>                          kept_here_;
      std::vector<std::vector<Entry>>            entries_;
      std::vector<double>                        c_;
      /** Per Dirichlet row: its row and the prescribed dof (body, dof). */
      struct DirichletRow
      {
        unsigned int row, body, dof;
      };
      std::vector<DirichletRow> dirichlet_rows_;
      unsigned int              n_gluing_ = 0, n_dirichlet_ = 0;
    };
  } // namespace decomposition
} // namespace dualcontact
