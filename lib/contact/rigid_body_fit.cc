#include <deal.II/base/exceptions.h>

#include <contact/rigid_body_fit.h>

#include <algorithm>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    RigidBodyFit<dim>::RigidBodyFit(
      const ContactDiscretization<dim>  &contact,
      const ContactRows<dim>            &rows,
      const std::vector<unsigned int>   &frictional_nodes,
      const std::vector<Vector<double>> &rigid_modes,
      const std::vector<Vector<double>> &G_rows)
        : contact_(contact)
        , rows_(rows)
        , frictional_nodes_(frictional_nodes)
        , rigid_modes_(rigid_modes)
        , G_rows_(G_rows)
    {
    }


    template <int dim>
    bool
    RigidBodyFit<dim>::add(Vector<double>                  &u,
                           const std::vector<unsigned int> &owned_rows,
                           const std::vector<bool>         &active,
                           const MPI_Comm                   communicator,
                           const bool require_determined) const
    {
      const unsigned int n_nodes = contact_.n_nodes();
      // alpha = (G_A G_A')^{-1} G_A (-r_A): G_A' alpha = -r_A in the
      // least-squares sense, r the residual of the constraints without
      // the rigid motion, r = B u - [c; -o_T] (= d - F lambda)
      const Vector<double> c = contact_.normal_bound();
      const unsigned int   m = rigid_modes_.size();
      // GGt and rhs in one buffer, summed over the processes
      std::vector<double> sums(m * m + m, 0.), total(m * m + m);
      for (unsigned int l = 0; l < owned_rows.size(); ++l)
      {
        if (!active[l])
          continue;
        const unsigned int r        = owned_rows[l];
        double             residual = rows_.row_times(r, u);
        if (r < n_nodes)
          residual -= c(r);
        else
        {
          const unsigned int t =
            (dim - 1) * frictional_nodes_[(r - n_nodes) / (dim - 1)] +
            (r - n_nodes) % (dim - 1);
          residual += contact_.tangential_offset()(t);
          if (previous_slip_ != nullptr && previous_slip_->size() > 0)
            residual -= (*previous_slip_)(t);
        }
        for (unsigned int k = 0; k < m; ++k)
        {
          sums[m * m + k] -= G_rows_[k](r) * residual;
          for (unsigned int l2 = 0; l2 < m; ++l2)
            sums[k * m + l2] += G_rows_[k](r) * G_rows_[l2](r);
        }
      }
      Utilities::MPI::sum(sums, communicator, total);
      FullMatrix<double> GGt(m, m);
      Vector<double>     rhs(m);
      for (unsigned int k = 0; k < m; ++k)
      {
        rhs(k) = total[m * m + k];
        for (unsigned int l2 = 0; l2 < m; ++l2)
          GGt(k, l2) = total[k * m + l2];
      }
      return add_rigid_motion(GGt, rhs, u, require_determined);
    }


    template <int dim>
    bool
    RigidBodyFit<dim>::add_rigid_motion(FullMatrix<double>   &GGt,
                                        const Vector<double> &rhs,
                                        Vector<double>       &u,
                                        const bool require_determined) const
    {
      const unsigned int m    = rigid_modes_.size();
      double             diag = 0;
      for (unsigned int k = 0; k < m; ++k)
        diag = std::max(diag, GGt(k, k));
      AssertThrow(diag > 0 || !require_determined,
                  ExcMessage("The rigid-body motion of a floating body is "
                             "not determined: no active contact "
                             "constraint holds it."));
      if (!(diag > 0))
        return false;
      // Tikhonov-free solve; a singular G_A G_A' means a mode that no
      // active constraint sees (e.g. tangential motion without
      // friction): it is left at zero by the pseudo-inverse below.
      for (unsigned int k = 0; k < m; ++k)
        GGt(k, k) += 1e-14 * diag;
      FullMatrix<double> inverse(m, m);
      inverse.invert(GGt);
      Vector<double> alpha(m);
      inverse.vmult(alpha, rhs);
      for (unsigned int k = 0; k < m; ++k)
        u.add(alpha(k), rigid_modes_[k]);
      return true;
    }


    template class RigidBodyFit<2>;
    template class RigidBodyFit<3>;
  } // namespace contact
} // namespace dualcontact
