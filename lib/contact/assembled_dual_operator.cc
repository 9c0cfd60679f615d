#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/lapack_templates.h>

#include <contact/assembled_dual_operator.h>
#include <util/blas.h>

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
      std::vector<double>       Fb;
      std::ostringstream        sizes;
      std::vector<unsigned int> local_index;
      unsigned int              n_inverted = 0;
      for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const types::blas_int c = schur[b].dofs.size();
        const types::blas_int r = rows[b].size();
        sizes << (b == 0 ? "" : ", ") << c;
        if (c == 0 || r == 0)
          continue;
        // (B_b)_C by rows: the entries of row q at the positions k of C
        const types::global_dof_index offset = contact.body_offset(b);
        local_index.assign(bodies[b]->n_dofs(), numbers::invalid_unsigned_int);
        for (types::blas_int k = 0; k < c; ++k)
          local_index[schur[b].dofs[k]] = k;
        std::vector<std::vector<std::pair<unsigned int, double>>> B_C(r);
        std::size_t                                               n_entries = 0;
        for (types::blas_int q = 0; q < r; ++q)
        {
          B.for_each_in_row(
            rows[b][q],
            [&](const types::global_dof_index column, const double value)
            {
              if (column < offset || column >= offset + bodies[b]->n_dofs())
                return;
              const unsigned int k = local_index[column - offset];
              if (k != numbers::invalid_unsigned_int)
                B_C[q].emplace_back(k, value);
            });
          n_entries += B_C[q].size();
        }
        // F_b = B_C S^{-1} B_C' (S = L L'), lower triangle, by the cheaper
        // of two routes.  Their flops (multiply-adds):
        //   W = L^{-1} B_C' (dtrtrs), F_b = W'W (dsyrk): c^2 r / 2 + c r^2 / 2
        //   S^{-1} = L^{-T} L^{-1} (dpotri: c^3 / 3), then two sparse
        //   products with B_C: 2 nnz(B_C) (c + r)
        // With every row of B touching one dof of C, as on a rigid plane
        // with an axis normal (c = r), the second is 3 times cheaper.
        const double c_d = c, r_d = r;
        const double by_triangular_solve =
          c_d * c_d * r_d / 2 + c_d * r_d * r_d / 2;
        const double by_inverse =
          c_d * c_d * c_d / 3 + 2. * n_entries * (c_d + r_d);
        Fb.assign(static_cast<std::size_t>(r) * r, 0.);
        if (by_inverse < by_triangular_solve)
          inverse_route(b, c, B_C, schur[b].lower, Fb);
        else
          triangular_solve_route(b, c, B_C, schur[b].lower, Fb);
        n_inverted += by_inverse < by_triangular_solve;
        std::vector<double>().swap(schur[b].lower); // not needed any more
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
           << " dense; Schur complements of size " << sizes.str();
      if (n_inverted > 0)
        line << "; " << n_inverted << " of them inverted";
      line << ")";
      description_ = line.str();
    }


    template <int dim>
    void
    AssembledDualOperator<dim>::triangular_solve_route(
      const unsigned int                                               body,
      const int                                                        c,
      const std::vector<std::vector<std::pair<unsigned int, double>>> &B_C,
      const std::vector<double>                                       &lower,
      std::vector<double>                                             &Fb)
    {
      // W = (B_b)_C' as a dense c x r matrix, then W = L^{-1} W, F_b = W'W
      const types::blas_int n = c, r = B_C.size();
      std::vector<double>   W(static_cast<std::size_t>(n) * r, 0.);
      for (types::blas_int q = 0; q < r; ++q)
        for (const auto &[k, value] : B_C[q])
          W[static_cast<std::size_t>(q) * n + k] += value;
      types::blas_int info = 0;
      trtrs("L", "N", "N", &n, &r, lower.data(), &n, W.data(), &n, &info);
      AssertThrow(info == 0,
                  ExcMessage("Dual operator: the Schur factor of body " +
                             std::to_string(body + 1) + " is singular."));
      const double one = 1., zero = 0.;
      syrk("L", "T", &r, &n, &one, W.data(), &n, &zero, Fb.data(), &r);
    }


    template <int dim>
    void
    AssembledDualOperator<dim>::inverse_route(
      const unsigned int                                               body,
      const int                                                        c,
      const std::vector<std::vector<std::pair<unsigned int, double>>> &B_C,
      std::vector<double>                                             &lower,
      std::vector<double>                                             &Fb)
    {
      // S^{-1} in place of L (lower triangle), then made whole
      const types::blas_int n    = c;
      const std::size_t     r    = B_C.size();
      types::blas_int       info = 0;
      potri("L", &n, lower.data(), &n, &info);
      AssertThrow(info == 0,
                  ExcMessage("Dual operator: the Schur factor of body " +
                             std::to_string(body + 1) + " is singular."));
      std::vector<double> &S_inverse = lower;
      for (std::size_t j = 0; j < static_cast<std::size_t>(c); ++j)
        for (std::size_t i = j + 1; i < static_cast<std::size_t>(c); ++i)
          S_inverse[i * c + j] = S_inverse[j * c + i];
      // T = S^{-1} B_C' (c x r), then the lower triangle of B_C T
      std::vector<double> T(static_cast<std::size_t>(c) * r, 0.);
      for (std::size_t q = 0; q < r; ++q)
        for (const auto &[k, value] : B_C[q])
        {
          const double *column = S_inverse.data() + k * c;
          double       *target = T.data() + q * c;
          for (std::size_t i = 0; i < static_cast<std::size_t>(c); ++i)
            target[i] += value * column[i];
        }
      for (std::size_t q = 0; q < r; ++q)
        for (std::size_t p = q; p < r; ++p)
        {
          double sum = 0;
          for (const auto &[k, value] : B_C[p])
            sum += value * T[q * c + k];
          Fb[q * r + p] = sum;
        }
    }


    template <int dim>
    void
    AssembledDualOperator<dim>::subtract_symmetric_update(
      const std::vector<unsigned int>  &rows,
      const dealii::FullMatrix<double> &X,
      const dealii::FullMatrix<double> &G)
    {
      const std::size_t  r = rows.size();
      const unsigned int k = G.m();
      AssertDimension(X.m(), r);
      AssertDimension(X.n(), k);
      AssertDimension(G.n(), r);
      const std::size_t m = m_;
      for (std::size_t q = 0; q < r; ++q)
        for (std::size_t p = 0; p < r; ++p)
        {
          double update = 0;
          for (unsigned int j = 0; j < k; ++j)
            update += X(p, j) * G(j, q) + G(j, p) * X(q, j);
          F_dense_[rows[q] * m + rows[p]] -= update;
        }
    }


    template <int dim>
    void
    AssembledDualOperator<dim>::vmult(VectorType       &dst,
                                      const VectorType &src) const
    {
      // dsymv reads one triangle: half the memory traffic of dgemv, which
      // is what a product of a matrix beyond the caches costs (1167
      // multipliers, 10.9 MB: 0.29 ms instead of 0.46 ms)
      const int    m = m_, one = 1;
      const double alpha = 1., beta = 0.;
      dst.reinit(m, true);
      dsymv_("L",
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
      owners.layout().gather(src, work_lambda_);
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
