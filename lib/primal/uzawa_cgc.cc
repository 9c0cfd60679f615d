#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <primal/complete_cholesky.h>
#include <primal/incomplete_cholesky.h>
#include <primal/uzawa_cgc.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dualcontact
{
  namespace primal
  {
    namespace
    {
      using VectorType = dealii::Vector<double>;


      /**
       * x += A_V' w with (A_V A_V') w = t: the least-norm change of x that
       * changes the rows V by t (CG on the Gram matrix, regular since the
       * rows are independent).
       */
      void
      add_least_norm_correction(
        const qp::LinearInequalities                       &rows,
        const std::vector<dealii::types::global_dof_index> &V,
        const std::vector<double>                          &t,
        VectorType                                         &x)
      {
        const std::size_t m = V.size();
        if (m == 0)
          return;
        VectorType work(x.size());
        const auto gram =
          [&](const std::vector<double> &in, std::vector<double> &out)
        {
          work = 0.;
          rows.add_transpose(V, in, work);
          for (std::size_t i = 0; i < m; ++i)
            out[i] = rows.row_dot(V[i], work);
        };
        const auto dot =
          [](const std::vector<double> &a, const std::vector<double> &b)
        {
          double s = 0.;
          for (std::size_t i = 0; i < a.size(); ++i)
            s += a[i] * b[i];
          return s;
        };
        std::vector<double> w(m, 0.), r(t), p(t), q(m);
        const double        norm_t = std::sqrt(dot(t, t));
        double              rr     = dot(r, r);
        for (unsigned int it = 0; it < 10 * m + 100 && rr > 0.; ++it)
        {
          gram(p, q);
          const double alpha = rr / dot(p, q);
          for (std::size_t i = 0; i < m; ++i)
          {
            w[i] += alpha * p[i];
            r[i] -= alpha * q[i];
          }
          const double rr_new = dot(r, r);
          if (std::sqrt(rr_new) <= 1e-15 * norm_t)
            break;
          for (std::size_t i = 0; i < m; ++i)
            p[i] = r[i] + rr_new / rr * p[i];
          rr = rr_new;
        }
        rows.add_transpose(V, w, x);
      }


      /**
       * A point with A x <= c: x = 0 if c >= 0 (the report's start, remark
       * 7.1), else the least-norm solution of A_V x = c_V over the rows V
       * with c_i < 0, which satisfies every row if the rows of A are
       * independent.
       */
      void
      feasible_start(const qp::LinearInequalities &rows, VectorType &x)
      {
        x = 0.;
        std::vector<dealii::types::global_dof_index> V;
        std::vector<double>                          t;
        for (std::size_t i = 0; i < rows.n_rows(); ++i)
          if (rows.right_hand_side(i) < 0.)
          {
            V.push_back(i);
            t.push_back(rows.right_hand_side(i));
          }
        add_least_norm_correction(rows, V, t, x);
      }


      /**
       * Puts the warm start of the next CGC solve back onto the rows it
       * violates by rounding: the previous solution stays on its facet only
       * up to the accuracy of the facet projections (after many CG steps
       * with dense rows, as PCG-1's A E^{-T}, more than CGC's start test
       * accepts).
       */
      void
      restore_feasibility(const qp::LinearInequalities &rows, VectorType &x)
      {
        // every row that is violated or nearly active is put exactly on its
        // bound (CGC counts those rows as active anyway); a few rounds in
        // case the correction moves a neighbouring row
        for (unsigned int round = 0; round < 3; ++round)
        {
          std::vector<dealii::types::global_dof_index> V;
          std::vector<double>                          t;
          bool                                         violated = false;
          for (std::size_t i = 0; i < rows.n_rows(); ++i)
          {
            const double slack = rows.slack(i, x);
            const double scale =
              std::abs(rows.right_hand_side(i)) + rows.row_abs_dot(i, x);
            if (slack <= 1e-10 * scale)
            {
              V.push_back(i);
              t.push_back(slack);
              violated = violated || slack < 0.;
            }
          }
          if (!violated)
            return;
          add_least_norm_correction(rows, V, t, x);
        }
      }

    } // namespace


    template <int dim>
    UzawaCGC<dim>::UzawaCGC(
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const contact::ContactDiscretization<dim>        &contact,
      const PrimalParameters                           &parameters,
      const contact::CoulombParameters                 &coulomb_parameters)
        : bodies_(bodies)
        , contact_(contact)
        , parameters_(parameters)
        , coulomb_parameters_(coulomb_parameters)
    {
      const auto n = contact.n_dofs();
      // the block-diagonal K of all bodies
      dealii::DynamicSparsityPattern dsp(n, n);
      for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const auto  offset = contact.body_offset(b);
        const auto &K      = bodies[b]->stiffness_matrix();
        for (unsigned int i = 0; i < K.m(); ++i)
          for (auto it = K.begin(i); it != K.end(i); ++it)
            dsp.add(offset + i, offset + it->column());
      }
      pattern_.copy_from(dsp);
      K_.reinit(pattern_);
      load_.reinit(n);
      for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const auto  offset = contact.body_offset(b);
        const auto &K      = bodies[b]->stiffness_matrix();
        for (unsigned int i = 0; i < K.m(); ++i)
          for (auto it = K.begin(i); it != K.end(i); ++it)
            K_.set(offset + i, offset + it->column(), it->value());
        for (unsigned int i = 0; i < K.m(); ++i)
          load_(offset + i) = bodies[b]->load_vector()(i);
      }

      // non-penetration rows B_N u <= c; a row without unknowns (slave and
      // master fully prescribed) is either void or infeasible
      rows_ = std::make_shared<qp::LinearInequalities>();
      const VectorType                             c  = contact.normal_bound();
      const auto                                  &BN = contact.normal_matrix();
      std::vector<dealii::types::global_dof_index> columns;
      std::vector<double>                          values;
      for (unsigned int i = 0; i < contact.n_nodes(); ++i)
      {
        columns.clear();
        values.clear();
        for (auto it = BN.begin(i); it != BN.end(i); ++it)
          if (it->value() != 0.)
          {
            columns.push_back(it->column());
            values.push_back(it->value());
          }
        if (columns.empty())
        {
          AssertThrow(c(i) >= -1e-14 * (1. + std::abs(contact.gaps()(i))),
                      dealii::ExcMessage(
                        "primal solver: contact node " + std::to_string(i) +
                        " has prescribed slave and master displacements "
                        "that penetrate by " +
                        std::to_string(-c(i)) + " m"));
          continue;
        }
        // gaps and offsets computed to rounding (a projected node on its
        // master face, a prescribed displacement along the surface) give
        // c_i = +-1e-15 m where the exact value is 0; such c_i count as 0,
        // so that u = 0 is feasible as in the report (remark 7.1)
        const double length =
          std::pow(contact.nodes()[i].weight, 1. / std::max(1, dim - 1));
        const double c_i = std::abs(c(i)) <= 1e-12 * length ? 0. : c(i);
        rows_->add_row(columns, values, c_i);
        row_node_.push_back(i);
      }

      frictional_index_.assign(contact.n_nodes(), -1);
      for (unsigned int i = 0; i < contact.n_nodes(); ++i)
        if (contact.pairs()[contact.nodes()[i].pair].friction.has_friction())
        {
          frictional_index_[i] = frictional_nodes_.size();
          frictional_nodes_.push_back(i);
        }
      per_edge_ = parameters.friction_multipliers == "per edge";
      if (!per_edge_)
        for (unsigned int j = 0; j < frictional_nodes_.size(); ++j)
          for (unsigned int k = 0; k + 1 < dim; ++k)
          {
            mult_rows_.push_back({{(dim - 1) * j + k, 1.}});
            mult_source_.push_back(j);
          }
      else
      {
        for (const auto &pair : contact.pairs())
          AssertThrow(!pair.friction.is_coulomb(),
                      dealii::ExcMessage(
                        "Friction multipliers = per edge needs given "
                        "(Tresca) friction; contact pair `" +
                        pair.name +
                        "' has Coulomb friction (`set Friction multipliers "
                        "= per node' in `subsection Primal solver')."));
        for (const auto &face : contact.faces())
        {
          if (!contact.pairs()[face.pair].friction.has_friction())
            continue;
          for (unsigned int k = 0; k + 1 < dim; ++k)
          {
            std::vector<std::pair<unsigned int, double>> entries;
            for (const auto &[node, w] : face.nodes)
              if (frictional_index_[node] >= 0)
                entries.emplace_back((dim - 1) * frictional_index_[node] + k,
                                     w);
            mult_rows_.push_back(entries);
            mult_source_.push_back(face.pair);
          }
        }
      }
      psi_.reinit(mult_rows_.size());
      mu_.reinit(psi_.size());
      u_.reinit(n);

      AssertThrow(parameters.version == "pcg1" || parameters.version == "pcg2",
                  dealii::ExcMessage("primal solver: Version must be pcg1 "
                                     "or pcg2, got `" +
                                     parameters.version + "'"));
      preconditioner_ =
        Preconditioner::create(parameters.preconditioner, parameters.omega);
      pcg1_ = preconditioner_ != nullptr && parameters.version == "pcg1";
    }


    template <int dim>
    UzawaCGC<dim>::~UzawaCGC() = default;


    template <int dim>
    const dealii::SparseMatrix<double> &
    UzawaCGC<dim>::stiffness_matrix() const
    {
      return K_;
    }


    template <int dim>
    void
    UzawaCGC<dim>::tangential_slip(const VectorType &u,
                                   VectorType       &dst,
                                   const bool        with_offset) const
    {
      const auto &BT = contact_.tangential_matrix();
      const auto &oT = contact_.tangential_offset();
      VectorType  rows((dim - 1) * frictional_nodes_.size());
      for (unsigned int j = 0; j < frictional_nodes_.size(); ++j)
        for (unsigned int k = 0; k + 1 < dim; ++k)
        {
          const unsigned int row = (dim - 1) * frictional_nodes_[j] + k;
          double             sum = with_offset ? oT(row) : 0.;
          for (auto it = BT.begin(row); it != BT.end(row); ++it)
            sum += it->value() * u(it->column());
          rows((dim - 1) * j + k) = sum;
        }
      dst.reinit(mult_rows_.size());
      for (unsigned int m = 0; m < mult_rows_.size(); ++m)
        for (const auto &[r, c] : mult_rows_[m])
          dst(m) += c * rows(r);
    }


    template <int dim>
    typename UzawaCGC<dim>::VectorType
    UzawaCGC<dim>::to_rows(const VectorType &v) const
    {
      VectorType rows((dim - 1) * frictional_nodes_.size());
      for (unsigned int m = 0; m < mult_rows_.size(); ++m)
        for (const auto &[r, c] : mult_rows_[m])
          rows(r) += c * v(m);
      return rows;
    }


    template <int dim>
    void
    UzawaCGC<dim>::add_tangential_transpose(const VectorType &w,
                                            VectorType       &dst) const
    {
      const VectorType rows = to_rows(w);
      const auto      &BT   = contact_.tangential_matrix();
      for (unsigned int j = 0; j < frictional_nodes_.size(); ++j)
        for (unsigned int k = 0; k + 1 < dim; ++k)
        {
          const unsigned int row = (dim - 1) * frictional_nodes_[j] + k;
          const double       wk  = rows((dim - 1) * j + k);
          for (auto it = BT.begin(row); it != BT.end(row); ++it)
            dst(it->column()) += it->value() * wk;
        }
    }


    template <int dim>
    void
    UzawaCGC<dim>::update_slip_bounds(const VectorType *lambda_N)
    {
      for (unsigned int m = 0; m < mult_rows_.size(); ++m)
      {
        const unsigned int k = m % (dim - 1);
        if (per_edge_)
        {
          // psi_f = g: the face's G row already carries int_f phi_i ds
          const contact::FrictionLaw &law =
            contact_.pairs()[mult_source_[m]].friction;
          psi_(m) = (k == 1 && law.is_orthotropic()) ? law.second : law.first;
          continue;
        }
        const unsigned int          node = frictional_nodes_[mult_source_[m]];
        const auto                 &n    = contact_.nodes()[node];
        const contact::FrictionLaw &law  = contact_.pairs()[n.pair].friction;
        const double                value[2] = {law.first,
                                 law.is_orthotropic() ? law.second : law.first};
        psi_(m) =
          law.is_coulomb() ?
            (lambda_N != nullptr ? value[k] * std::max(0., (*lambda_N)(node)) :
                                   0.) :
            value[k] * n.weight;
      }
    }


    template <int dim>
    double
    UzawaCGC<dim>::estimate_lipschitz()
    {
      const Preconditioner *inverse = preconditioner_.get();
      if (parameters_.preconditioner != "cholesky")
      {
        if (!cholesky_)
        {
          cholesky_ = std::make_unique<CompleteCholesky>();
          cholesky_->initialize(K_);
        }
        inverse = cholesky_.get();
      }
      VectorType v(psi_.size()), Mv(psi_.size()), w(K_.m()), z(K_.m());
      for (unsigned int i = 0; i < v.size(); ++i)
        v(i) = 1. + 0.1 * std::sin(1. + i);
      v /= v.l2_norm();
      double lambda = 0.;
      for (unsigned int it = 0; it < 200; ++it)
      {
        // M v = psi B_T K^{-1} B_T' psi v
        VectorType pv(v);
        pv.scale(psi_);
        w = 0.;
        add_tangential_transpose(pv, w);
        inverse->apply_inverse(z, w);
        tangential_slip(z, Mv, false);
        Mv.scale(psi_);
        const double lambda_new = v * Mv;
        const double norm       = Mv.l2_norm();
        if (norm == 0.)
          return 0.;
        v = Mv;
        v /= norm;
        if (std::abs(lambda_new - lambda) <= 1e-6 * lambda_new)
          return lambda_new;
        lambda = lambda_new;
      }
      return lambda;
    }


    template <int dim>
    qp::SolverStatistics
    UzawaCGC<dim>::solve_qp(Result &result)
    {
      // b = f - B_T' (psi mu)
      VectorType b(load_);
      if (psi_.size() > 0)
      {
        VectorType w(mu_);
        w.scale(psi_);
        w *= -1.;
        add_tangential_transpose(w, b);
      }

      typename qp::CGC<VectorType>::AdditionalData data;
      data.tolerance       = parameters_.cgc_tolerance;
      data.max_iterations  = parameters_.cgc_max_iterations;
      data.loose_tolerance = parameters_.cgc_loose_tolerance;
      data.n_loose         = parameters_.cgc_loose_iterations;
      data.release =
        qp::CGC<VectorType>::release_names.value(parameters_.cgc_release);
      data.stopping_test = qp::CGC<VectorType>::stopping_test_names.value(
        parameters_.cgc_stopping_test);
      qp::CGC<VectorType> cgc(data);

      qp::SolverStatistics stats;
      dealii::Timer        timer;
      if (pcg1_)
      {
        // PCG-1 = CG(C) on the transformed problem in y = E'u: Hessian
        // E^{-1} K E^{-T}, load E^{-1} b, rows A E^{-T}
        const Preconditioner      &E = *preconditioner_;
        qp::CGCProblem<VectorType> problem;
        VectorType                 t(K_.m()), Kt(K_.m());
        problem.hessian = [&](VectorType &dst, const VectorType &src)
        {
          E.apply_E_inverse_transpose(t, src);
          K_.vmult(Kt, t);
          E.apply_E_inverse(dst, Kt);
        };
        E.apply_E_inverse(problem.b, b);
        problem.constraints = transformed_rows_;
        if (!started_)
        {
          y_.reinit(K_.m());
          feasible_start(*transformed_rows_, y_);
        }
        else
          restore_feasibility(*transformed_rows_, y_);
        stats = cgc.solve(problem, y_);
        E.apply_E_inverse_transpose(u_, y_);
      }
      else
      {
        qp::CGCProblem<VectorType> problem;
        problem.hessian = [this](VectorType &dst, const VectorType &src)
        { K_.vmult(dst, src); };
        problem.b           = b;
        problem.constraints = rows_;
        if (preconditioner_)
        {
          const Preconditioner &E = *preconditioner_;
          cgc.set_split_preconditioner(
            [&E](VectorType &dst, const VectorType &src)
            { E.apply_E_inverse(dst, src); },
            [&E](VectorType &dst, const VectorType &src)
            { E.apply_E_inverse_transpose(dst, src); });
        }
        if (!started_)
          feasible_start(*rows_, u_);
        else
          restore_feasibility(*rows_, u_);
        stats = cgc.solve(problem, u_);
      }
      result.cgc_time += timer.wall_time();
      multipliers_ = cgc.multipliers();
      if (!started_)
      {
        result.first_cgc   = stats;
        result.first_outer = cgc.outer_log();
      }
      started_ = true;
      ++result.n_cgc_solves;
      result.total_inner_iterations += stats.iterations;
      result.total_outer_iterations += stats.n_outer;
      result.worst_cgc_criterion =
        std::max(result.worst_cgc_criterion, stats.final_criterion);
      return stats;
    }


    template <int dim>
    bool
    UzawaCGC<dim>::uzawa(Result &result)
    {
      const bool friction = psi_.size() > 0 && psi_.linfty_norm() > 0.;
      if (!friction)
      {
        const auto stats = solve_qp(result);
        if (!stats.converged())
        {
          result.reason = "CGC did not converge (" +
                          qp::to_string(stats.reason) + ", criterion " +
                          std::to_string(stats.final_criterion) +
                          "): " + stats.message;
          return false;
        }
        return true;
      }

      dealii::Timer timer;
      result.lipschitz = estimate_lipschitz();
      result.setup_time += timer.wall_time();
      result.rho = parameters_.uzawa_step > 0. ?
                     parameters_.uzawa_step :
                     parameters_.uzawa_step_factor / result.lipschitz;
      VectorType slip, mu_new(mu_.size());
      for (unsigned int k = 0; k < parameters_.uzawa_max_iterations; ++k)
      {
        const auto stats = solve_qp(result);
        if (!stats.converged())
        {
          result.reason =
            "CGC did not converge in Uzawa iteration " + std::to_string(k + 1) +
            " (" + qp::to_string(stats.reason) + ", criterion " +
            std::to_string(stats.final_criterion) + "): " + stats.message;
          return false;
        }
        ++result.uzawa_iterations;
        // mu <- Pi(mu + rho psi (B_T u + o_T)), Pi onto the unit ball of
        // every node (|mu_i| <= 1 in 2D)
        tangential_slip(u_, slip);
        double change = 0., change_sq = 0.;
        for (unsigned int j = 0; j < mu_.size() / (dim - 1); ++j)
        {
          double norm_sq = 0.;
          for (unsigned int c = 0; c + 1 < dim; ++c)
          {
            const unsigned int r = (dim - 1) * j + c;
            mu_new(r)            = mu_(r) + result.rho * psi_(r) * slip(r);
            norm_sq += mu_new(r) * mu_new(r);
          }
          const double scale = norm_sq > 1. ? 1. / std::sqrt(norm_sq) : 1.;
          for (unsigned int c = 0; c + 1 < dim; ++c)
          {
            const unsigned int r = (dim - 1) * j + c;
            mu_new(r) *= scale;
            change = std::max(change, std::abs(mu_new(r) - mu_(r)));
            change_sq += (mu_new(r) - mu_(r)) * (mu_new(r) - mu_(r));
          }
        }
        // the report's form (remark 7.2): ||mu^{k+1} - mu^k|| / max(1,
        // ||mu^k||)
        if (parameters_.uzawa_stopping_test == "relative")
          change = std::sqrt(change_sq) / std::max(1., mu_.l2_norm());
        result.mu_changes.push_back(change);
        // (u, mu) is the answer when mu is a fixed point of the update
        if (change <= parameters_.uzawa_tolerance)
          return true;
        mu_ = mu_new;
      }
      std::ostringstream text;
      text << "Uzawa iteration limit " << parameters_.uzawa_max_iterations
           << " reached, last change of mu " << result.mu_changes.back()
           << " > tolerance " << parameters_.uzawa_tolerance;
      result.reason = text.str();
      return false;
    }


    template <int dim>
    typename UzawaCGC<dim>::Result
    UzawaCGC<dim>::solve()
    {
      dealii::Timer timer;
      Result        result;
      result.preconditioner =
        preconditioner_ ? preconditioner_->name() : std::string("none");
      result.version       = parameters_.version;
      result.n_constraints = rows_->n_rows();
      result.n_unknowns    = K_.m();
      started_             = false;
      u_                   = 0.;
      mu_                  = 0.;

      if (preconditioner_)
      {
        dealii::Timer setup;
        preconditioner_->initialize(K_);
        if (const auto *ic =
              dynamic_cast<const IncompleteCholesky *>(preconditioner_.get()))
          result.ic_shift = ic->shift();
        if (pcg1_)
        {
          // the rows of A E^{-T}: a_i' E^{-T} = (E^{-1} a_i)'
          transformed_rows_ = std::make_shared<qp::LinearInequalities>();
          VectorType                                   a(K_.m()), ea(K_.m());
          std::vector<dealii::types::global_dof_index> columns;
          std::vector<double>                          values;
          for (unsigned int i = 0; i < rows_->n_rows(); ++i)
          {
            a = 0.;
            rows_->add_transpose({i}, {1.}, a);
            preconditioner_->apply_E_inverse(ea, a);
            columns.clear();
            values.clear();
            for (unsigned int k = 0; k < ea.size(); ++k)
              if (ea(k) != 0.)
              {
                columns.push_back(k);
                values.push_back(ea(k));
              }
            transformed_rows_->add_row(columns,
                                       values,
                                       rows_->right_hand_side(i));
          }
        }
        result.setup_time += setup.wall_time();
      }

      const bool coulomb  = std::any_of(contact_.pairs().begin(),
                                       contact_.pairs().end(),
                                       [](const auto &pair)
                                       { return pair.friction.is_coulomb(); });
      const auto lambda_N = [this]()
      {
        VectorType l(contact_.n_nodes());
        for (const auto &[row, value] : multipliers_)
          l(row_node_[row]) = value;
        return l;
      };

      update_slip_bounds(nullptr);
      bool ok = uzawa(result);
      ++result.n_tresca;
      if (ok && coulomb)
      {
        // fixed point psi = mu_F lambda_N over Tresca problems
        contact::CoulombFixedPoint fixed_point(coulomb_parameters_);
        ok = false;
        for (;;)
        {
          const VectorType psi_old(psi_);
          const VectorType l = lambda_N();
          update_slip_bounds(&l);
          VectorType diff(psi_);
          diff -= psi_old;
          const contact::CoulombFixedPoint::State state =
            fixed_point.record_change(
              contact::CoulombFixedPoint::relative_change(diff.norm_sqr(),
                                                          psi_.norm_sqr()));
          if (state == contact::CoulombFixedPoint::State::converged)
          {
            psi_ = psi_old; // (u, lambda) belong to the old bounds
            ok   = true;
            break;
          }
          if (state != contact::CoulombFixedPoint::State::iterating)
          {
            result.reason = fixed_point.message();
            break;
          }
          if (!uzawa(result))
            break;
          ++result.n_tresca;
        }
      }
      result.converged = ok;
      if (ok)
        result.reason = "converged";

      // results: distributed displacements and the dual-layout multipliers
      result.displacements.resize(bodies_.size());
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        auto &d = result.displacements[b];
        d.reinit(bodies_[b]->n_dofs());
        for (unsigned int i = 0; i < d.size(); ++i)
          d(i) = u_(contact_.body_offset(b) + i);
        bodies_[b]->distribute(d);
      }
      // per frictional row: the force sum_m c_{m,r} psi_m mu_m and the
      // bound sum_m c_{m,r} psi_m (per node: psi mu and psi)
      VectorType psi_mu(psi_);
      psi_mu.scale(mu_);
      const VectorType force      = to_rows(psi_mu);
      result.friction_multipliers = mu_;
      const VectorType bound      = to_rows(psi_);
      result.lambda.reinit(contact_.n_nodes() + force.size());
      const VectorType l = lambda_N();
      for (unsigned int i = 0; i < contact_.n_nodes(); ++i)
        result.lambda(i) = l(i);
      for (unsigned int r = 0; r < force.size(); ++r)
        result.lambda(contact_.n_nodes() + r) = force(r);
      result.slip_bounds_first.assign(frictional_nodes_.size(), 0.);
      result.slip_bounds_second.assign(frictional_nodes_.size(), 0.);
      for (unsigned int j = 0; j < frictional_nodes_.size(); ++j)
      {
        result.slip_bounds_first[j]  = bound((dim - 1) * j);
        result.slip_bounds_second[j] = bound((dim - 1) * j + dim - 2);
      }
      result.total_time = timer.wall_time();
      return result;
    }


    template <int dim>
    std::string
    UzawaCGC<dim>::Result::to_json() const
    {
      nlohmann::json outer = nlohmann::json::array();
      for (const auto &o : first_outer)
        outer.push_back({{"active", o.n_active},
                         {"facet", o.n_facet},
                         {"inner", o.inner_iterations}});
      nlohmann::json json = {
        {"method", "uzawa-cgc"},
        {"preconditioner", preconditioner},
        {"version", version},
        {"converged", converged},
        {"reason", reason},
        {"n_constraints", n_constraints},
        {"n_unknowns", n_unknowns},
        {"uzawa_iterations", uzawa_iterations},
        {"tresca_problems", n_tresca},
        {"rho", rho},
        {"norm_G_Kinv_Gt", lipschitz},
        {"last_mu_change", mu_changes.empty() ? 0. : mu_changes.back()},
        {"mu_changes", mu_changes},
        {"cgc_solves", n_cgc_solves},
        {"inner_iterations", total_inner_iterations},
        {"outer_iterations", total_outer_iterations},
        {"worst_cgc_criterion", worst_cgc_criterion},
        {"ic_shift", ic_shift},
        {"setup_time_s", setup_time},
        {"cgc_time_s", cgc_time},
        {"total_time_s", total_time},
        {"first_cgc",
         {{"outer", outer},
          {"iterations", first_cgc.iterations},
          {"hessian_products", first_cgc.n_hessian_products},
          {"reason", qp::to_string(first_cgc.reason)},
          {"criterion", first_cgc.final_criterion},
          {"wall_time_s", first_cgc.wall_time}}}};
      return json.dump();
    }


    template class UzawaCGC<2>;
    template class UzawaCGC<3>;
  } // namespace primal
} // namespace dualcontact
