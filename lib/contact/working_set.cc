#include <deal.II/base/exceptions.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <contact/working_set.h>
#include <qp/separable_set.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace dualcontact
{
  namespace contact
  {
    void
    WorkingSetParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Dual problem");
      prm.enter_subsection("Working set");
      prm.declare_entry(
        "Enabled",
        "true",
        dealii::Patterns::Bool(),
        "Solve the dual first on the normal contact rows that can close: a "
        "slave node whose bound (gap) exceeds the smallest of its pair by "
        "more than the reach is left out (multiplier fixed at 0), the "
        "displacement is then checked at every left-out node and any that "
        "penetrates is added back and the QP solved again, until none does. "
        "The answer is that of the whole problem; without it the gaps of "
        "far nodes dominate the dual's right-hand side and stiff or far-apart "
        "bodies do not converge (doc/stability.md). Rows dropped and added "
        "back are in statistics.json (contact.working_sets).");
      prm.declare_entry("Reach factor",
                        "10",
                        dealii::Patterns::Double(0.),
                        "reach = factor * (largest normal displacement of a "
                        "slave node under the loads alone, without contact, "
                        "+ largest prescribed normal displacement) [-]; "
                        "rows with a bound within the reach of their pair's "
                        "smallest (or of 0) are kept from the start.");
      prm.declare_entry("Maximum rounds",
                        "20",
                        dealii::Patterns::Integer(1),
                        "Limit on the solve / check / add-back rounds of one "
                        "QP; beyond it the QP is solved on all rows.");
      prm.declare_entry(
        "Drop separated rows",
        "false",
        dealii::Patterns::Bool(),
        "true: the QP is solved in rounds from the separation tolerance down "
        "to its own; after each, the normal rows whose multiplier is 0 and "
        "whose node is open in the recovered displacement are left out too "
        "(a row once added back stays), and the last round is checked as "
        "above. Why: such a row's column of G = R'B' ties the rigid-body "
        "modes of its subdomain to a multiplier that cannot move, and "
        "SMALSE-M's coarse projector then describes the wrong equality "
        "(TFETI). Measured (doc/benchmarks/tfeti.md, 'Separated rows'): 2 to "
        "6 times fewer iterations where separated rows dominate (a brick "
        "hanging above its obstacle, 3D Hertz), twice as many on the "
        "friction brick; hence off by default.");
      prm.declare_entry("Separation tolerance",
                        "0.1",
                        dealii::Patterns::Double(0., 1.),
                        "Relative tolerance of the first round that looks "
                        "for separated rows (the QP solver's own tolerance "
                        "where that is larger) [-].");
      prm.declare_entry("Separation reduction",
                        "0.1",
                        dealii::Patterns::Double(1e-6, 0.9),
                        "Factor from one round's tolerance to the next "
                        "while separated rows are looked for, down to the "
                        "QP solver's tolerance [-].");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    void
    WorkingSetParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Dual problem");
      prm.enter_subsection("Working set");
      enabled              = prm.get_bool("Enabled");
      reach_factor         = prm.get_double("Reach factor");
      max_rounds           = prm.get_integer("Maximum rounds");
      drop_separated_rows  = prm.get_bool("Drop separated rows");
      separation_tolerance = prm.get_double("Separation tolerance");
      separation_reduction = prm.get_double("Separation reduction");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    template <int dim>
    WorkingSet<dim>::WorkingSet(const DualFormulation<dim>    &dual,
                                const qp::Problem<VectorType> &full,
                                const WorkingSetParameters    &parameters)
        : dual_(dual)
        , full_(full)
        , parameters_(parameters)
        , kept_(full.b.size(), true)
        , locked_(dual.contact().n_nodes(), false)
    {
      select_rows();
      update_index();
    }


    template <int dim>
    void
    WorkingSet<dim>::select_rows()
    {
      const ContactDiscretization<dim> &contact = dual_.contact();
      const unsigned int                n_nodes = contact.n_nodes();
      const dealii::Vector<double>     &c       = contact.normal_bound();
      const dealii::Vector<double>     &offset  = contact.normal_offset();
      record_.n_normal_rows                     = n_nodes;
      if (!parameters_.enabled || n_nodes == 0)
        return;

      // the slave nodes' normal displacement under the loads alone:
      // d = B K^# f - c, and b = d / s in the scaled QP
      double load_reach = 0, prescribed = 0;
      for (unsigned int i = 0; i < n_nodes; ++i)
      {
        load_reach =
          std::max(load_reach, std::abs(dual_.scale() * full_.b(i) + c(i)));
        prescribed = std::max(prescribed, std::abs(offset(i)));
      }
      const double reach = parameters_.reach_factor * (load_reach + prescribed);
      record_.reach      = reach;

      std::vector<double> smallest(contact.pairs().size(),
                                   std::numeric_limits<double>::infinity());
      for (unsigned int i = 0; i < n_nodes; ++i)
      {
        const unsigned int p = contact.nodes()[i].pair;
        smallest[p]          = std::min(smallest[p], c(i));
      }
      for (unsigned int i = 0; i < n_nodes; ++i)
      {
        const double base = std::max(smallest[contact.nodes()[i].pair], 0.);
        if (c(i) > base + reach)
        {
          kept_[i] = false;
          ++record_.n_dropped;
        }
      }
      record_.used            = record_.n_dropped > 0;
      record_.n_dropped_final = record_.n_dropped;
    }


    template <int dim>
    void
    WorkingSet<dim>::update_index()
    {
      index_.clear();
      for (unsigned int r = 0; r < kept_.size(); ++r)
        if (kept_[r])
          index_.push_back(r);
    }


    template <int dim>
    bool
    WorkingSet<dim>::drops_rows() const
    {
      return index_.size() < kept_.size();
    }


    template <int dim>
    void
    WorkingSet<dim>::gather(const VectorType &whole, VectorType &kept) const
    {
      kept.reinit(index_.size());
      for (unsigned int k = 0; k < index_.size(); ++k)
        kept(k) = whole(index_[k]);
    }


    template <int dim>
    void
    WorkingSet<dim>::scatter(const VectorType &kept, VectorType &whole) const
    {
      whole.reinit(kept_.size());
      for (unsigned int k = 0; k < index_.size(); ++k)
        whole(index_[k]) = kept(k);
    }


    namespace
    {
      /** Largest order of G_W G_W' factorized densely. */
      constexpr unsigned int max_dense_coarse_order = 3000;

      /**
       * Rows of @p equality (B = G~_W: the orthonormal rows of the full
       * problem restricted to the kept columns, no longer orthonormal)
       * made orthonormal again: B := L^{-1} B, c := L^{-1} c with
       * B B' = L L' (dense, of the order of the rigid-body modes), so
       * that SMALSE-M keeps its coarse projector on the working set.  Left
       * as it is (penalty form) when B B' is too large for a dense factor
       * or numerically singular (a mode that only left-out rows hold).
       */
      void
      orthonormalize_rows(
        qp::EqualityConstraints<dealii::Vector<double>> &equality)
      {
        const unsigned int m = equality.c.size();
        if (m == 0 || m > max_dense_coarse_order)
          return;
        dealii::LAPACKFullMatrix<double> BBt(m, m);
        dealii::Vector<double>           unit(m), column(m), Bt;
        for (unsigned int j = 0; j < m; ++j)
        {
          unit    = 0.;
          unit(j) = 1.;
          equality.Tvmult(Bt, unit);
          equality.vmult(column, Bt);
          for (unsigned int i = 0; i < m; ++i)
            BBt(i, j) = column(i);
        }
        double largest = 0;
        for (unsigned int i = 0; i < m; ++i)
          largest = std::max(largest, BBt(i, i));
        try
        {
          BBt.compute_cholesky_factorization();
        }
        catch (...)
        {
          return;
        }
        // the pivots: L_ii^2 below 1e-12 of the largest diagonal entry of
        // B B' is a mode the kept columns do not hold; L as a triangular
        // matrix, for LAPACK's triangular solves
        auto L = std::make_shared<dealii::LAPACKFullMatrix<double>>(m, m);
        for (unsigned int i = 0; i < m; ++i)
        {
          if (!(BBt(i, i) * BBt(i, i) > 1e-12 * largest))
            return;
          for (unsigned int k = 0; k <= i; ++k)
            (*L)(i, k) = BBt(i, k);
        }
        L->set_property(dealii::LAPACKSupport::lower_triangular);
        equality.vmult =
          [vmult = equality.vmult, L](dealii::Vector<double>       &dst,
                                      const dealii::Vector<double> &src)
        {
          vmult(dst, src);
          L->solve(dst);
        };
        equality.Tvmult =
          [Tvmult = equality.Tvmult, L](dealii::Vector<double>       &dst,
                                        const dealii::Vector<double> &src)
        {
          dealii::Vector<double> y = src;
          L->solve(y, true);
          Tvmult(dst, y);
        };
        L->solve(equality.c);
        equality.norm_sq          = 1.;
        equality.orthonormal_rows = true;
      }
    } // namespace


    template <int dim>
    qp::Problem<typename WorkingSet<dim>::VectorType>
    WorkingSet<dim>::reduced_problem() const
    {
      qp::Problem<VectorType> reduced;
      const unsigned int      n = kept_.size();
      // A_WW x = (A E x)_W, E the extension by zeros
      reduced.hessian = [this, n](VectorType &dst, const VectorType &src)
      {
        VectorType whole(n), product(n);
        scatter(src, whole);
        full_.hessian(product, whole);
        gather(product, dst);
      };
      gather(full_.b, reduced.b);
      // the preconditioner in face of the full problem, with the left-out
      // rows active (their multipliers are fixed at 0): M_F is then one of
      // the kept free rows, as the solver asks
      if (full_.free_set_preconditioner)
        reduced.free_set_preconditioner =
          [this, n](const VectorType &active_kept)
        {
          VectorType active(n);
          active = 1.;
          for (unsigned int k = 0; k < index_.size(); ++k)
            active(index_[k]) = active_kept(k);
          return [this, n, apply = full_.free_set_preconditioner(active)](
                   VectorType &dst, const VectorType &src)
          {
            VectorType whole(n), result(n);
            scatter(src, whole);
            apply(result, whole);
            gather(result, dst);
          };
        };
      // an upper bound of the full A is one of A_WW
      reduced.lambda_max   = full_.lambda_max;
      reduced.semidefinite = full_.semidefinite;

      std::vector<int> new_index(n, -1);
      for (unsigned int k = 0; k < index_.size(); ++k)
        new_index[index_[k]] = k;
      auto set = std::make_shared<qp::SeparableSet<VectorType>>();
      dual_.add_contact_blocks(*set, new_index);
      set->finalize(reduced.b);
      reduced.constraints = set;

      if (full_.equality)
      {
        const qp::EqualityConstraints<VectorType> &G = *full_.equality;
        auto equality = std::make_shared<qp::EqualityConstraints<VectorType>>();
        equality->vmult = [this, n, &G](VectorType &dst, const VectorType &src)
        {
          VectorType whole(n);
          scatter(src, whole);
          G.vmult(dst, whole);
        };
        equality->Tvmult = [this, &G](VectorType &dst, const VectorType &src)
        {
          VectorType whole;
          G.Tvmult(whole, src);
          gather(whole, dst);
        };
        equality->c             = G.c;
        equality->n_constraints = G.n_constraints;
        // dropping columns does not increase ||G||
        equality->norm_sq                  = G.norm_sq;
        equality->projector_penalty_factor = G.projector_penalty_factor;
        if (G.orthonormal_rows)
          orthonormalize_rows(*equality);
        reduced.equality = equality;

        // b := b - G_W' beta, beta the least-squares fit of b by the rows
        // of G_W (normal equations G_W G_W' beta = G_W b, of the order of
        // the rigid-body modes, by conjugate gradients: G_W G_W' may be
        // singular when few rows are kept; CG then converges to a
        // least-squares solution, which is all the shift needs)
        const unsigned int m = G.c.size();
        VectorType         rhs, beta(m), r, p, q(m), Gt;
        equality->vmult(rhs, reduced.b);
        r                 = rhs;
        p                 = r;
        double       rr   = r * r;
        const double stop = 1e-28 * std::max(rr, 1e-300);
        for (unsigned int it = 0; it < 2 * m && rr > stop; ++it)
        {
          equality->Tvmult(Gt, p);
          equality->vmult(q, Gt);
          const double pq = p * q;
          if (!(pq > 0))
            break;
          const double alpha = rr / pq;
          beta.add(alpha, p);
          r.add(-alpha, q);
          const double rr_new = r * r;
          p.sadd(rr_new / rr, r);
          rr = rr_new;
        }
        equality->Tvmult(Gt, beta);
        reduced.b -= Gt;
        // The relative stopping tests of the solvers refer to ||b||, and
        // after the shift b can be nothing but rounding (when the kept rows
        // fit the rigid-body modes exactly) while the solution is of the
        // size of the loads e.  So add back G_W' gamma, gamma along e, with
        // ||G_W' gamma||^2 = target^2 - ||b||^2 (b is orthogonal to the
        // range of G_W' now): exact as the shift, and ||b|| = target,
        // target = min(||e||, ||b|| of the whole problem): the loads where
        // far gaps dominate the whole b (the floating cylinder), and never
        // a looser test than the whole problem's (TFETI, where the loads on
        // the floating subdomains can be many times ||b||: the separated
        // rows of a hanging brick solved against ||e|| left interface jumps
        // 100 times those of the whole problem at the same tolerance)
        const double norm_b = reduced.b.l2_norm();
        const double target = std::min(G.c.l2_norm(), full_.b.l2_norm());
        equality->Tvmult(Gt, G.c);
        const double norm_Gte = Gt.l2_norm();
        if (norm_b < target && norm_Gte > 0)
          reduced.b.add(std::sqrt(target * target - norm_b * norm_b) / norm_Gte,
                        Gt);
      }
      return reduced;
    }


    template <int dim>
    std::pair<double, double>
    WorkingSet<dim>::normal_gap(
      const unsigned int                         i,
      const std::vector<dealii::Vector<double>> &u) const
    {
      const ContactDiscretization<dim> &contact = dual_.contact();
      const auto                       &B       = contact.normal_matrix();
      const double                      c       = contact.normal_bound()(i);
      double                            Bu = 0, size = std::abs(c);
      for (auto it = B.begin(i); it != B.end(i); ++it)
      {
        const unsigned int b = contact.body_of_dof(it->column());
        const double       term =
          it->value() * u[b](it->column() - contact.body_offset(b));
        Bu += term;
        size += std::abs(term);
      }
      return {c - Bu, size};
    }


    template <int dim>
    unsigned int
    WorkingSet<dim>::add_violated_rows(
      const std::vector<dealii::Vector<double>> &u)
    {
      unsigned int added = 0;
      for (unsigned int i = 0; i < dual_.contact().n_nodes(); ++i)
      {
        if (kept_[i])
          continue;
        // a row dropped for its reach is far from closing, one dropped as
        // separated was open: rounding of the sum is far below any
        // penetration that matters
        const auto [gap, size] = normal_gap(i, u);
        if (-gap > 1e-12 * size)
        {
          kept_[i]   = true;
          locked_[i] = true;
          ++added;
        }
      }
      record_.n_added += added;
      record_.n_dropped_final -= added;
      if (added > 0)
        update_index();
      return added;
    }


    template <int dim>
    bool
    WorkingSet<dim>::separates_rows() const
    {
      return parameters_.enabled && parameters_.drop_separated_rows &&
             dual_.contact().n_nodes() > 0;
    }


    template <int dim>
    unsigned int
    WorkingSet<dim>::drop_separated_rows(
      const VectorType                          &lambda,
      const std::vector<dealii::Vector<double>> &u)
    {
      unsigned int dropped = 0;
      for (unsigned int i = 0; i < dual_.contact().n_nodes(); ++i)
      {
        if (!kept_[i] || locked_[i] || lambda(i) > 0.)
          continue;
        const auto [gap, size] = normal_gap(i, u);
        if (gap > 1e-12 * size)
        {
          kept_[i] = false;
          ++dropped;
        }
      }
      record_.n_separated += dropped;
      record_.n_dropped_final += dropped;
      // a first solve was made: the record tells, even if nothing dropped
      record_.used = true;
      if (dropped > 0)
        update_index();
      return dropped;
    }


    template <int dim>
    const WorkingSetRecord &
    WorkingSet<dim>::record() const
    {
      return record_;
    }


    template <int dim>
    WorkingSetRecord &
    WorkingSet<dim>::record()
    {
      return record_;
    }


    template class WorkingSet<2>;
    template class WorkingSet<3>;
  } // namespace contact
} // namespace dualcontact
