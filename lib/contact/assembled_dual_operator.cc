#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/lapack_templates.h>

#include <contact/assembled_dual_operator.h>

#include <sstream>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    AssembledDualOperator<dim>::AssembledDualOperator(
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const ContactDiscretization<dim>                 &contact,
      const ContactRows<dim>                           &B,
      std::vector<fem::StiffnessSolver::SchurFactor>   &schur,
      const std::vector<std::vector<unsigned int>>     &rows)
        : m_(B.n_rows())
    {
      Timer                 timer;
      const types::blas_int m = m_;
      F_dense_.assign(static_cast<std::size_t>(m) * m, 0.);
      std::vector<double>       W, Fb;
      std::ostringstream        sizes;
      std::vector<unsigned int> local_index;
      for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const types::blas_int c = schur[b].dofs.size();
        const types::blas_int r = rows[b].size();
        sizes << (b == 0 ? "" : ", ") << c;
        if (c == 0 || r == 0)
          continue;
        // W = (B_b)_C' as a dense c x r matrix, then W = L^{-1} W.
        const types::global_dof_index offset = contact.body_offset(b);
        local_index.assign(bodies[b]->n_dofs(), numbers::invalid_unsigned_int);
        for (types::blas_int k = 0; k < c; ++k)
          local_index[schur[b].dofs[k]] = k;
        W.assign(static_cast<std::size_t>(c) * r, 0.);
        for (types::blas_int q = 0; q < r; ++q)
          B.for_each_in_row(
            rows[b][q],
            [&](const types::global_dof_index column, const double value)
            {
              if (column < offset || column >= offset + bodies[b]->n_dofs())
                return;
              const unsigned int k = local_index[column - offset];
              if (k != numbers::invalid_unsigned_int)
                W[static_cast<std::size_t>(q) * c + k] += value;
            });
        types::blas_int info = 0;
        trtrs("L",
              "N",
              "N",
              &c,
              &r,
              schur[b].lower.data(),
              &c,
              W.data(),
              &c,
              &info);
        AssertThrow(info == 0,
                    ExcMessage("Dual operator: the Schur factor of body " +
                               std::to_string(b + 1) + " is singular."));
        std::vector<double>().swap(schur[b].lower); // not needed any more
        // F_b = W'W (lower triangle), scattered into F.
        Fb.assign(static_cast<std::size_t>(r) * r, 0.);
        const double one = 1., zero = 0.;
        syrk("L", "T", &r, &c, &one, W.data(), &c, &zero, Fb.data(), &r);
        for (types::blas_int q = 0; q < r; ++q)
          for (types::blas_int p = q; p < r; ++p)
          {
            const double value = Fb[static_cast<std::size_t>(q) * r + p];
            F_dense_[static_cast<std::size_t>(rows[b][q]) * m + rows[b][p]] +=
              value;
            if (p != q)
              F_dense_[static_cast<std::size_t>(rows[b][p]) * m + rows[b][q]] +=
                value;
          }
      }
      assembly_time_ = timer.wall_time();
      std::ostringstream line;
      line << "assembled (" << m << " x " << m
           << " dense; Schur complements of size " << sizes.str() << ")";
      description_ = line.str();
    }


    template <int dim>
    void
    AssembledDualOperator<dim>::vmult(VectorType       &dst,
                                      const VectorType &src) const
    {
      const types::blas_int m = m_, one = 1;
      const double          alpha = 1., beta = 0.;
      dst.reinit(m, true);
      gemv("N",
           &m,
           &m,
           &alpha,
           F_dense_.data(),
           &m,
           src.begin(),
           &one,
           &beta,
           dst.begin(),
           &one);
    }


    template <int dim>
    void
    AssembledDualOperator<dim>::vmult(
      DistributedVector            &dst,
      const DistributedVector      &src,
      const MultiplierDistribution &owners) const
    {
      // the whole src, then the owned rows of F (= columns, F is
      // symmetric and column-major) by runs of consecutive rows
      const std::vector<unsigned int> &owned_rows = owners.owned_rows();
      owners.gather(src, work_lambda_);
      const types::blas_int m = m_, one = 1;
      const double          alpha = 1., beta = 0.;
      for (unsigned int k = 0; k < owned_rows.size();)
      {
        unsigned int end = k + 1;
        while (end < owned_rows.size() &&
               owned_rows[end] == owned_rows[end - 1] + 1)
          ++end;
        const types::blas_int n_rows = end - k;
        gemv("T",
             &m,
             &n_rows,
             &alpha,
             F_dense_.data() + static_cast<std::size_t>(owned_rows[k]) * m,
             &m,
             work_lambda_.begin(),
             &one,
             &beta,
             dst.begin() + k,
             &one);
        k = end;
      }
    }


    template <int dim>
    bool
    AssembledDualOperator<dim>::is_assembled() const
    {
      return !F_dense_.empty();
    }


    template <int dim>
    const std::string &
    AssembledDualOperator<dim>::description() const
    {
      return description_;
    }


    template <int dim>
    double
    AssembledDualOperator<dim>::assembly_time() const
    {
      return assembly_time_;
    }


    template class AssembledDualOperator<2>;
    template class AssembledDualOperator<3>;
  } // namespace contact
} // namespace dualcontact
