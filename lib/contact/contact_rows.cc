#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <contact/contact_rows.h>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    ContactRows<dim>::ContactRows(
      const ContactDiscretization<dim> &contact,
      const std::vector<unsigned int>  &frictional_nodes)
        : contact_(contact)
        , frictional_nodes_(frictional_nodes)
    {
    }


    template <int dim>
    unsigned int
    ContactRows<dim>::n_rows() const
    {
      return contact_.n_nodes() + (dim - 1) * frictional_nodes_.size();
    }


    template <int dim>
    void
    ContactRows<dim>::vmult(Vector<double>       &lambda,
                            const Vector<double> &u) const
    {
      const unsigned int n_nodes = contact_.n_nodes();
      lambda.reinit(n_rows(), true);
      Vector<double> normal(n_nodes);
      contact_.normal_matrix().vmult(normal, u);
      for (unsigned int i = 0; i < n_nodes; ++i)
        lambda(i) = normal(i);
      if (!frictional_nodes_.empty())
      {
        work_t_.reinit((dim - 1) * n_nodes, true);
        contact_.tangential_matrix().vmult(work_t_, u);
        for (unsigned int j = 0; j < frictional_nodes_.size(); ++j)
          for (unsigned int k = 0; k + 1 < dim; ++k)
            lambda(n_nodes + (dim - 1) * j + k) =
              work_t_((dim - 1) * frictional_nodes_[j] + k);
      }
    }


    template <int dim>
    void
    ContactRows<dim>::Tvmult(Vector<double>       &u,
                             const Vector<double> &lambda) const
    {
      const unsigned int n_nodes = contact_.n_nodes();
      u.reinit(contact_.n_dofs());
      Vector<double> normal(n_nodes);
      for (unsigned int i = 0; i < n_nodes; ++i)
        normal(i) = lambda(i);
      contact_.normal_matrix().Tvmult(u, normal);
      if (!frictional_nodes_.empty())
      {
        work_t_.reinit((dim - 1) * n_nodes);
        for (unsigned int j = 0; j < frictional_nodes_.size(); ++j)
          for (unsigned int k = 0; k + 1 < dim; ++k)
            work_t_((dim - 1) * frictional_nodes_[j] + k) =
              lambda(n_nodes + (dim - 1) * j + k);
        contact_.tangential_matrix().Tvmult_add(u, work_t_);
      }
    }


    template <int dim>
    void
    ContactRows<dim>::Tvmult_owned(Vector<double>                      &u,
                                   const TrilinosWrappers::MPI::Vector &lambda,
                                   const std::vector<unsigned int> &owned_rows,
                                   const MPI_Comm communicator) const
    {
      u.reinit(contact_.n_dofs());
      for (unsigned int k = 0; k < owned_rows.size(); ++k)
      {
        const double value = lambda.begin()[k];
        if (value != 0.)
          for_each_in_row(owned_rows[k],
                          [&](const types::global_dof_index column,
                              const double                  entry)
                          { u(column) += entry * value; });
      }
      const int ierr = MPI_Allreduce(
        MPI_IN_PLACE, u.begin(), u.size(), MPI_DOUBLE, MPI_SUM, communicator);
      AssertThrowMPI(ierr);
    }


    template <int dim>
    double
    ContactRows<dim>::row_times(const unsigned int    r,
                                const Vector<double> &u) const
    {
      double value = 0;
      for_each_in_row(r,
                      [&](const types::global_dof_index column,
                          const double entry) { value += entry * u(column); });
      return value;
    }


    template class ContactRows<2>;
    template class ContactRows<3>;
  } // namespace contact
} // namespace dualcontact
