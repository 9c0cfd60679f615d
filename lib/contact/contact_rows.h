#pragma once

#include <deal.II/base/types.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <contact/contact_discretization.h>

#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * The rows B = [B_N; B_T] of the undecomposed dual in the multipliers'
     * layout [lambda_N (one per contact node); lambda_T (dim - 1 per
     * frictional node, in node order)]: B_N of every contact node, B_T of
     * the frictional ones only (ContactDiscretization holds B_T for every
     * node).  Columns: the stacked dofs of all bodies.  What the implicit
     * dual operator, d, G = R'B' and the recovery apply.
     */
    template <int dim>
    class ContactRows
    {
    public:
      /**
       * @p frictional_nodes: the contact nodes with tangential rows, in
       * order (DualFormulation's); both arguments must outlive this
       * object.
       */
      ContactRows(const ContactDiscretization<dim> &contact,
                  const std::vector<unsigned int>  &frictional_nodes);

      /** Rows of B: the multipliers. */
      unsigned int
      n_rows() const;

      /** Calls @p f(column, value) for the entries of row @p r of B. */
      template <typename Function>
      void
      for_each_in_row(const unsigned int r, const Function &f) const;

      /** lambda = B u (@p lambda is resized to n_rows()). */
      void
      vmult(dealii::Vector<double>       &lambda,
            const dealii::Vector<double> &u) const;

      /** u = B' lambda (@p u is resized to the dofs of all bodies). */
      void
      Tvmult(dealii::Vector<double>       &u,
             const dealii::Vector<double> &lambda) const;

      /**
       * u = B' lambda from the owned multipliers only (@p owned_rows: their
       * rows, in @p lambda's local order), summed over the processes of
       * @p communicator: u whole on every process.  Collective.
       */
      void
      Tvmult_owned(dealii::Vector<double>                      &u,
                   const dealii::TrilinosWrappers::MPI::Vector &lambda,
                   const std::vector<unsigned int>             &owned_rows,
                   MPI_Comm communicator) const;

      /** Row @p r of B u. */
      double
      row_times(const unsigned int r, const dealii::Vector<double> &u) const;

    private:
      const ContactDiscretization<dim> &contact_;
      const std::vector<unsigned int>  &frictional_nodes_;
      /** B_T u of all nodes (the frictional ones' rows are picked). */
      mutable dealii::Vector<double> work_t_;
    };


    template <int dim>
    template <typename Function>
    void
    ContactRows<dim>::for_each_in_row(const unsigned int r,
                                      const Function    &f) const
    {
      const unsigned int n_nodes = contact_.n_nodes();
      if (r < n_nodes)
      {
        const auto &B = contact_.normal_matrix();
        for (auto it = B.begin(r); it != B.end(r); ++it)
          f(it->column(), it->value());
      }
      else
      {
        const unsigned int j   = (r - n_nodes) / (dim - 1);
        const unsigned int k   = (r - n_nodes) % (dim - 1);
        const unsigned int row = (dim - 1) * frictional_nodes_[j] + k;
        const auto        &B   = contact_.tangential_matrix();
        for (auto it = B.begin(row); it != B.end(row); ++it)
          f(it->column(), it->value());
      }
    }
  } // namespace contact
} // namespace dualcontact
