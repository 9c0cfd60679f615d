#include <deal.II/base/exceptions.h>

#include <decomposition/tfeti_dual.h>

// TFETIDual's linear terms, d and e: formed at the construction and again
// for every load step (update_load()); apart from tfeti_dual.cc to keep
// files short.

namespace dualcontact
{
  namespace decomposition
  {
    using namespace dealii;

    template <int dim>
    void
    TFETIDual<dim>::update_load(const VectorType &previous_slip)
    {
      AssertThrow(previous_slip.size() == 0 ||
                    previous_slip.size() == (dim - 1) * contact_.n_nodes(),
                  ExcDimensionMismatch(previous_slip.size(),
                                       (dim - 1) * contact_.n_nodes()));
      previous_slip_ = previous_slip;
      // the loads' integrals of the owned subdomains only: K_s, its
      // factor and the kernel R_s do not depend on the load
      for (const unsigned int s : owned_)
        subdomains_[s]->assemble_load();
      rows_->update_rhs(contact_, frictional_nodes_);
      form_row_rhs();
      form_coarse_rhs();
      form_linear_term();
      if (distributed_)
        distribute_linear_terms();
    }


    template <int dim>
    void
    TFETIDual<dim>::form_row_rhs()
    {
      c_.reinit(n_multipliers());
      for (unsigned int r = 0; r < n_multipliers(); ++r)
        c_(r) = rows_->rhs(r);
      // friction on the slip increment (design.md, "Load history"): a
      // sticking node keeps B_T u + o_T = s, i.e. B_T u = c_T + s with
      // c_T = -o_T; the same shift as the undecomposed dual's
      // d_T = (B K^+ f)_T + o_T - s
      if (previous_slip_.size() == 0)
        return;
      const unsigned int n_nodes = contact_.n_nodes();
      for (unsigned int j = 0; j < frictional_nodes_.size(); ++j)
        for (unsigned int k = 0; k + 1 < dim; ++k)
          c_(n_nodes + (dim - 1) * j + k) +=
            previous_slip_((dim - 1) * frictional_nodes_[j] + k);
    }


    template <int dim>
    void
    TFETIDual<dim>::form_coarse_rhs()
    {
      const unsigned int n_rigid = dim * (dim + 1) / 2;
      e_.reinit(coarse_->n_modes());
      for (const unsigned int s : owned_)
      {
        const auto &modes = subdomains_[s]->modes();
        for (unsigned int k = 0; k < n_rigid; ++k)
          e_(s * n_rigid + k) = modes[k] * subdomains_[s]->load();
      }
      sum_over_processes(e_);
      e_orthonormal_ = e_;
      coarse_->orthonormalize(e_orthonormal_);
    }


    template <int dim>
    void
    TFETIDual<dim>::form_linear_term()
    {
      std::vector<VectorType> f(subdomains_.size()), u;
      for (const unsigned int s : owned_)
        f[s] = subdomains_[s]->load();
      apply_K_inverse(f, u);
      d_.reinit(n_multipliers());
      add_B(u, d_.data());
      sum_over_processes(d_);
      d_ -= c_;
    }


    template <int dim>
    void
    TFETIDual<dim>::distribute_linear_terms()
    {
      ownership_->layout().extract(d_, *d_distributed_);
      for (unsigned int k = 0; k < e_distributed_->locally_owned_size(); ++k)
        e_distributed_->begin()[k] = e_orthonormal_(k);
    }


    // the members defined here, for the dimensions of TFETIDual's own
    // instantiation (tfeti_dual.cc)
    template void
    TFETIDual<2>::update_load(const VectorType &);
    template void
    TFETIDual<3>::update_load(const VectorType &);
    template void
    TFETIDual<2>::form_row_rhs();
    template void
    TFETIDual<3>::form_row_rhs();
    template void
    TFETIDual<2>::form_coarse_rhs();
    template void
    TFETIDual<3>::form_coarse_rhs();
    template void
    TFETIDual<2>::form_linear_term();
    template void
    TFETIDual<3>::form_linear_term();
    template void
    TFETIDual<2>::distribute_linear_terms();
    template void
    TFETIDual<3>::distribute_linear_terms();
  } // namespace decomposition
} // namespace dualcontact
