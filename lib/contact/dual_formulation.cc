#include <deal.II/base/exceptions.h>

#include <contact/dual_formulation.h>

#include <cmath>
#include <limits>
#include <numeric>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    DualFormulation<dim>::DualFormulation(
      const ContactDiscretization<dim> &contact)
        : contact_(contact)
    {
      // Frictional nodes: those of pairs with a friction law.
      frictional_index_.assign(contact.n_nodes(), -1);
      for (unsigned int i = 0; i < contact.n_nodes(); ++i)
        if (contact.pairs()[contact.nodes()[i].pair].friction.has_friction())
        {
          frictional_index_[i] = frictional_nodes_.size();
          frictional_nodes_.push_back(i);
        }
      psi_first_.assign(frictional_nodes_.size(), 0.);
      psi_second_.assign(frictional_nodes_.size(), 0.);
    }


    template <int dim>
    unsigned int
    DualFormulation<dim>::n_contact_multipliers() const
    {
      return contact_.n_nodes() + (dim - 1) * frictional_nodes_.size();
    }


    template <int dim>
    unsigned int
    DualFormulation<dim>::n_contact_nodes() const
    {
      return contact_.n_nodes();
    }


    template <int dim>
    unsigned int
    DualFormulation<dim>::n_frictional_nodes() const
    {
      return frictional_nodes_.size();
    }


    template <int dim>
    int
    DualFormulation<dim>::frictional_index(const unsigned int node) const
    {
      return frictional_index_[node];
    }


    template <int dim>
    bool
    DualFormulation<dim>::has_coulomb_friction() const
    {
      for (const auto &pair : contact_.pairs())
        if (pair.friction.is_coulomb())
          return true;
      return false;
    }


    template <int dim>
    void
    DualFormulation<dim>::set_slip_bounds(const std::vector<double> &first,
                                          const std::vector<double> &second)
    {
      AssertDimension(first.size(), frictional_nodes_.size());
      AssertDimension(second.size(), frictional_nodes_.size());
      psi_first_  = first;
      psi_second_ = second;
    }


    template <int dim>
    void
    DualFormulation<dim>::update_slip_bounds(const VectorType *lambda)
    {
      for (unsigned int j = 0; j < frictional_nodes_.size(); ++j)
      {
        const unsigned int      node = frictional_nodes_[j];
        const ContactNode<dim> &n    = contact_.nodes()[node];
        const FrictionLaw      &law  = contact_.pairs()[n.pair].friction;
        if (law.is_coulomb())
        {
          // Without multipliers yet: bonded (no bound), which is feasible
          // for any load; psi = 0 would forbid tangential forces and make
          // a body with a tangential load and no tangential support
          // infeasible.
          const double mu_1 = law.first;
          const double mu_2 = law.is_orthotropic() ? law.second : law.first;
          const double inf  = std::numeric_limits<double>::infinity();
          if (lambda)
          {
            const double lambda_n = std::max((*lambda)(node), 0.);
            psi_first_[j]         = mu_1 * lambda_n;
            psi_second_[j]        = mu_2 * lambda_n;
          }
          else
          {
            psi_first_[j]  = mu_1 > 0 ? inf : 0.;
            psi_second_[j] = mu_2 > 0 ? inf : 0.;
          }
        }
        else
        {
          psi_first_[j] = law.first * n.weight;
          psi_second_[j] =
            (law.is_orthotropic() ? law.second : law.first) * n.weight;
        }
      }
    }


    template <int dim>
    const std::vector<double> &
    DualFormulation<dim>::slip_bounds_first() const
    {
      return psi_first_;
    }


    template <int dim>
    const std::vector<double> &
    DualFormulation<dim>::slip_bounds_second() const
    {
      return psi_second_;
    }


    template <int dim>
    double
    DualFormulation<dim>::friction_utilization(const VectorType  &lambda,
                                               const unsigned int j) const
    {
      const unsigned int first = n_contact_nodes() + (dim - 1) * j;
      return friction_utilization(j, lambda.begin() + first);
    }


    template <int dim>
    double
    DualFormulation<dim>::friction_utilization(const unsigned int j,
                                               const double *tangential) const
    {
      const FrictionLaw &law =
        contact_.pairs()[contact_.nodes()[frictional_nodes_[j]].pair].friction;
      double ratio2 = 0;
      for (unsigned int k = 0; k + 1 < dim; ++k)
      {
        // ellipse semi-axes (psi_1, psi_2) for orthotropic laws in 3D
        const double bound = (dim == 3 && law.is_orthotropic() && k == 1) ?
                               psi_second_[j] :
                               psi_first_[j];
        const double value = tangential[k];
        if (std::isinf(bound))
          continue;
        if (bound > 0)
          ratio2 += (value / bound) * (value / bound);
        else if (value != 0)
          return std::numeric_limits<double>::infinity();
      }
      return std::sqrt(ratio2);
    }


    template <int dim>
    void
    DualFormulation<dim>::add_contact_blocks(
      qp::SeparableSet<VectorType> &set) const
    {
      std::vector<int> identity(n_contact_multipliers());
      std::iota(identity.begin(), identity.end(), 0);
      add_contact_blocks(set, identity);
    }


    template <int dim>
    template <typename V>
    void
    DualFormulation<dim>::add_contact_blocks(
      qp::SeparableSet<V>    &set,
      const std::vector<int> &new_index) const
    {
      const unsigned int n_nodes = contact_.n_nodes();
      for (unsigned int i = 0; i < n_nodes; ++i)
        if (new_index[i] >= 0)
          set.add_bound(new_index[i], 0.);
      for (unsigned int j = 0; j < frictional_nodes_.size(); ++j)
      {
        const int first = new_index[n_nodes + (dim - 1) * j];
        if (first < 0)
          continue;
        const FrictionLaw &law =
          contact_.pairs()[contact_.nodes()[frictional_nodes_[j]].pair]
            .friction;
        if (std::isinf(psi_first_[j]) || std::isinf(psi_second_[j]))
          continue;
        if (dim == 2)
          set.add_box(first, -psi_first_[j], psi_first_[j]);
        else if (law.is_orthotropic() && psi_first_[j] > 0 &&
                 psi_second_[j] > 0)
          set.add_ellipse(first, psi_first_[j], psi_second_[j]);
        else
          set.add_disc(first, std::min(psi_first_[j], psi_second_[j]));
      }
    }


    template <int dim>
    const ContactDiscretization<dim> &
    DualFormulation<dim>::contact() const
    {
      return contact_;
    }


    template <int dim>
    bool
    DualFormulation<dim>::contact_row_is_active(const VectorType  &lambda,
                                                const unsigned int r,
                                                const double tolerance) const
    {
      const unsigned int n_nodes = contact_.n_nodes();
      if (r < n_nodes)
        return lambda(r) > tolerance;
      // a Tresca bound acts whether or not the node is pressed, so a
      // separated node can stick; a zero bound (Coulomb without normal
      // force) constrains nothing
      const unsigned int j = (r - n_nodes) / (dim - 1);
      return std::max(psi_first_[j], psi_second_[j]) > 0 &&
             friction_utilization(lambda, j) < 1 - 1e-6;
    }


    template <int dim>
    bool
    DualFormulation<dim>::is_distributed() const
    {
      return false;
    }


    namespace
    {
      [[noreturn]] void
      throw_one_process_only()
      {
        AssertThrow(false,
                    ExcMessage("This dual problem runs its QP on one "
                               "process only (replicated vectors)."));
      }
    } // namespace


    template <int dim>
    void
    DualFormulation<dim>::initialize_multipliers(DistributedVector &) const
    {
      throw_one_process_only();
    }


    template <int dim>
    void
    DualFormulation<dim>::gather(const DistributedVector &, VectorType &) const
    {
      throw_one_process_only();
    }


    template <int dim>
    qp::Problem<typename DualFormulation<dim>::DistributedVector>
    DualFormulation<dim>::make_distributed_problem() const
    {
      throw_one_process_only();
    }


    template <int dim>
    void
    DualFormulation<dim>::update_slip_bounds(const DistributedVector &)
    {
      throw_one_process_only();
    }


    template <int dim>
    bool
    DualFormulation<dim>::recover(const DistributedVector &,
                                  std::vector<dealii::Vector<double>> &,
                                  const bool) const
    {
      throw_one_process_only();
    }


    template void
    DualFormulation<2>::add_contact_blocks(
      qp::SeparableSet<dealii::Vector<double>> &,
      const std::vector<int> &) const;
    template void
    DualFormulation<2>::add_contact_blocks(
      qp::SeparableSet<dealii::TrilinosWrappers::MPI::Vector> &,
      const std::vector<int> &) const;
    template void
    DualFormulation<3>::add_contact_blocks(
      qp::SeparableSet<dealii::Vector<double>> &,
      const std::vector<int> &) const;
    template void
    DualFormulation<3>::add_contact_blocks(
      qp::SeparableSet<dealii::TrilinosWrappers::MPI::Vector> &,
      const std::vector<int> &) const;
    template <int dim>
    void
    DualFormulation<dim>::update_load(const VectorType &)
    {
      AssertThrow(false,
                  dealii::ExcMessage(
                    "Load steps (`subsection Load steps') are not "
                    "supported by this dual formulation yet: use the "
                    "undecomposed dual (`set Method = none' in `subsection "
                    "Decomposition')."));
    }


    template class DualFormulation<2>;
    template class DualFormulation<3>;
  } // namespace contact
} // namespace dualcontact
