#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <decomposition/cell_partition.h>
#include <decomposition/tfeti_dual.h>
#include <fem/cholmod_solver.h>
#include <fem/rigid_body_modes.h>
#include <qp/power_iteration.h>
#include <qp/separable_set.h>
#include <util/machine.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace dualcontact
{
  namespace decomposition
  {
    using namespace dealii;

    namespace
    {
      /**
       * The parts of TFETI's QP that do not depend on the vectors'
       * distribution (make_problem(), make_distributed_problem()): the
       * bounds on lambda_max of the scaled F and of the scaled P F P (F / s
       * with s = lambda_max(P F P); Lanczos' estimates approach from below,
       * hence 5 % more), and what G~'s rows are.
       */
      template <typename V>
      void
      describe_scaled_problem(qp::Problem<V>             &problem,
                              qp::EqualityConstraints<V> &equality,
                              const unsigned int          n_modes,
                              const double                lambda_max_ratio,
                              const double projector_penalty_factor)
      {
        problem.lambda_max            = 1.05 * lambda_max_ratio;
        equality.projected_lambda_max = 1.05;
        equality.n_constraints        = n_modes;
        equality.norm_sq              = 1.; // ||G~||^2 = lambda_max(G~ G~') = 1
        // G~ G~' = L^-1 P G G' P' L^-T = I: SMALSE-M may use the coarse
        // projector
        equality.orthonormal_rows = true;
        // rho / lambda_max(P F P) unless the .prm says otherwise
        // (TFETIDual::projector_penalty_factor())
        equality.projector_penalty_factor = projector_penalty_factor;
        problem.semidefinite              = true;
      }
    } // namespace


    template <int dim>
    TFETIDual<dim>::TFETIDual(
      const std::vector<const fem::ElasticBody<dim> *>             &bodies,
      const contact::ContactDiscretization<dim>                    &contact,
      const DecompositionParameters                                &parameters,
      const std::function<std::unique_ptr<fem::StiffnessSolver>()> &make_solver,
      const MPI_Comm              communicator,
      const DistributedMesh<dim> *distributed_mesh)
        : contact::DualFormulation<dim>(contact)
        , communicator_(communicator)
        // a program that never initialized MPI (a test) runs on one process
        , n_processes_(Utilities::MPI::job_supports_mpi() ?
                         Utilities::MPI::n_mpi_processes(communicator) :
                         1)
        , rank_(Utilities::MPI::job_supports_mpi() ?
                  Utilities::MPI::this_mpi_process(communicator) :
                  0)
        , bodies_(bodies)
        , distributed_mesh_(distributed_mesh)
    {
      // hanging nodes and Dirichlet conditions become multiplier rows;
      // every other constraint line must be one of these
#ifdef DEBUG
      for (const auto *body : bodies_)
        for (const auto &line : body->constraints().get_lines())
          Assert(line.entries.empty() ||
                   body->hanging_node_constraints().is_constrained(line.index),
                 ExcInternalError());
#endif
      // a body whose Dirichlet conditions leave a rigid-body motion free
      for (unsigned int b = 0; b < bodies_.size(); ++b)
        has_floating_body_ =
          has_floating_body_ ||
          (distributed_mesh_ ?
             floats_on_distributed_mesh(b) :
             fem::RigidBodyModes<dim>(*bodies_[b]).n_modes() > 0);
      Timer timer;
      decompose(parameters);
      decomposition_time_ = max_over_processes(timer.wall_time());

      // Only the preconditioners apply K_s; the solves need its factor.
      // Released as soon as it is factorized, the peak holds one K_s
      // beside the factors instead of all of them (level-40 brick, 128
      // subdomains on two processes: peak 1.49 -> 1.33 GB a process).
      const bool keep_stiffness = parameters.preconditioner == "lumped" ||
                                  parameters.preconditioner == "dirichlet";
      timer.restart();
      for (const unsigned int s : owned_)
      {
        subdomains_[s]->factorize(make_solver());
        if (!keep_stiffness)
          subdomains_[s]->release_stiffness_matrix();
      }
      setup_time_ = max_over_processes(timer.wall_time());

      std::vector<bool> kept_here(subdomains_.size());
      for (unsigned int s = 0; s < subdomains_.size(); ++s)
        kept_here[s] = owner_[s] == rank_;
      rows_ = std::make_unique<ConstraintRows<dim>>(
        bodies_,
        contact_,
        frictional_nodes_,
        typename ConstraintRows<dim>::Layout{
          dofs_, first_subdomain_, first_copy_, kept_here},
        parameters.gluing);
      AssertThrow(rows_->n_rows() >= this->n_contact_multipliers(),
                  ExcInternalError());
      build_coarse_problem();
      if (keep_stiffness)
      {
        using Kind = typename DualPreconditioner<dim>::Kind;
        Timer preconditioner_timer;
        preconditioner_ = std::make_unique<DualPreconditioner<dim>>(
          parameters.preconditioner == "dirichlet" ? Kind::dirichlet :
                                                     Kind::lumped,
          *rows_,
          subdomains_,
          owned_,
          n_multipliers(),
          communicator_,
          make_solver,
          [this](VectorType                                            &dst,
                 const VectorType                                      &src,
                 const typename DualPreconditioner<dim>::LocalOperator &local)
          { apply_between_B(dst, src, local); });
        preconditioner_setup_time_ =
          max_over_processes(preconditioner_timer.wall_time());
      }

      // d = B K^+ f - c (the static problem: no previous slip)
      form_row_rhs();
      form_linear_term();

      estimate_scale();
      AssertThrow(scale_ > 0 && std::isfinite(scale_),
                  ExcMessage("The TFETI dual operator F is zero or not "
                             "finite."));

      nodes_per_process_ = {this->n_contact_nodes()};
      distributed_       = parameters.distributed_multipliers;
      AssertThrow(!distributed_ || Utilities::MPI::job_supports_mpi(),
                  ExcMessage("`set QP vectors = distributed' in `subsection "
                             "Dual problem' needs MPI (Trilinos vectors), "
                             "which this program did not initialize."));
      if (distributed_)
        distribute_multipliers();
      std::ostringstream description;
      description << "TFETI, implicit: local solves with the factors of "
                  << subdomains_.size() << " subdomains (K_s^+ from "
                  << (owned_.empty() ? std::string("none on process 0") :
                                       subdomains_[owned_[0]]->solver().name())
                  << ")";
      if (n_processes_ > 1)
      {
        description << " on " << n_processes_
                    << " processes (subdomains per process";
        const std::vector<unsigned int> per_process = subdomains_per_process();
        for (unsigned int p = 0; p < per_process.size(); ++p)
          description << (p == 0 ? " " : ", ") << per_process[p];
        description << (distributed_ ?
                          "), multipliers distributed: F lambda exchanged "
                          "between the processes that share rows" :
                          "), F lambda summed by MPI_Allreduce");
      }
      description << "; lambda_max(F) " << lambda_max_F_
                  << ", lambda_max(P F P) " << scale_
                  << " (the scale) by Lanczos in " << scale_products_
                  << " products";
      operator_description_ = description.str();
    }


    template <int dim>
    void
    TFETIDual<dim>::estimate_scale()
    {
      // Lanczos, not the power iteration: every product is a solve with
      // every subdomain's factor, and on the level-40 brick (128
      // subdomains) the power iteration took 143 of them to settle to 1e-6
      // where Lanczos takes 30.  Two estimates: the QP is scaled by
      // lambda_max(P F P), P = I - G~'G~, the operator SMALSE-M's coarse
      // projector iterates with (with K^# in place of K^+, lambda_max(F)
      // was 1.5e6 times it on 3D Hertz and made every step that much too
      // short; with K^+ it is 1.03 to 1.24 times it).  lambda_max(F) stays
      // the bound the penalty form (`Coarse projector = false') and the
      // working set's reduced problems need.
      const auto lanczos = [this](const auto &apply)
      { return qp::lanczos_lambda_max<VectorType>(apply, d_, 200, 1e-6, 1.0); };
      const qp::PowerIterationResult of_F = lanczos(
        [this](VectorType &dst, const VectorType &src) { apply_F(dst, src); });
      const qp::PowerIterationResult of_PFP = lanczos(
        [this](VectorType &dst, const VectorType &src)
        {
          VectorType y = src;
          project(y);
          apply_F(dst, y);
          project(dst);
        });
      lambda_max_F_   = of_F.estimate;
      scale_          = of_PFP.estimate;
      scale_products_ = of_F.n_products + of_PFP.n_products;
    }


    template <int dim>
    double
    TFETIDual<dim>::projector_penalty_factor() const
    {
      // Measured (products at factor 1 / 3; doc/benchmarks/tfeti.md,
      // "Pseudoinverses"): the friction brick, clamped, wants 3 (level 20
      // in 8 subdomains 810 / 788, level 40 in 128 not converged / 1,023;
      // 10: 805 and 1,444), and so do the 2D scenes (Tresca block 359 /
      // 204, cylinder 622 / 396, two bodies 104 / 61); the 3D scenes with
      // a floating body want 1 (3D Hertz 2,755 / 3,150, two Hertz bodies
      // 6,070 / 7,305, stacked Tresca boxes 231 / 352, the Coulomb block
      // at 20 x 20 x 5 6,521 / 16,337).
      return dim == 3 && has_floating_body_ ? 1. : 3.;
    }


    template <int dim>
    void
    TFETIDual<dim>::project(VectorType &v) const
    {
      // v - G~'G~ v
      VectorType coarse(coarse_->n_modes()), correction(v.size());
      coarse_->vmult(coarse, v);
      coarse_->orthonormalize(coarse);
      coarse_->orthonormalize_transpose(coarse);
      coarse_->Tvmult(correction, coarse);
      v -= correction;
    }


    template <int dim>
    double
    TFETIDual<dim>::max_over_processes(const double x) const
    {
      return n_processes_ > 1 ? Utilities::MPI::max(x, communicator_) : x;
    }


    template <int dim>
    void
    TFETIDual<dim>::sum_over_processes(VectorType &v) const
    {
      if (n_processes_ == 1)
        return;
      const int ierr = MPI_Allreduce(
        MPI_IN_PLACE, v.data(), v.size(), MPI_DOUBLE, MPI_SUM, communicator_);
      AssertThrowMPI(ierr);
    }


    template <int dim>
    void
    TFETIDual<dim>::build_coarse_problem()
    {
      const unsigned int     n_rigid = dim * (dim + 1) / 2;
      const unsigned int     n_modes = subdomains_.size() * n_rigid;
      CoarseProblem::Columns columns(n_multipliers());
      // the entries of R_s'B_s' of the owned subdomains, as (row, mode,
      // value) triples, gathered on every process
      std::vector<double> triples;
      for (const unsigned int s : owned_)
      {
        const auto &modes = subdomains_[s]->modes();
        AssertDimension(modes.size(), n_rigid);
        for (const Entry &entry : rows_->entries(s))
          for (unsigned int k = 0; k < n_rigid; ++k)
            triples.insert(triples.end(),
                           {static_cast<double>(entry.row),
                            static_cast<double>(s * n_rigid + k),
                            entry.value * modes[k](entry.local)});
      }
      if (n_processes_ > 1)
        triples = util::concatenate_over_processes(triples, communicator_);
      for (unsigned int t = 0; t < triples.size(); t += 3)
        columns[static_cast<unsigned int>(triples[t])].emplace_back(
          static_cast<unsigned int>(triples[t + 1]), triples[t + 2]);
      // merge the entries of a mode in a column (a contact row may touch
      // several dofs of one subdomain), in their order (stable: the same
      // sums on any number of processes)
      for (auto &column : columns)
      {
        std::stable_sort(column.begin(),
                         column.end(),
                         [](const auto &a, const auto &b)
                         { return a.first < b.first; });
        unsigned int n = 0;
        for (unsigned int q = 0; q < column.size(); ++q)
          if (n > 0 && column[n - 1].first == column[q].first)
            column[n - 1].second += column[q].second;
          else
            column[n++] = column[q];
        column.resize(n);
      }

      coarse_ = std::make_unique<CoarseProblem>(n_modes, std::move(columns));
      form_coarse_rhs();
    }


    template <int dim>
    void
    TFETIDual<dim>::apply_Bt(
      const double                                 *lambda,
      std::vector<VectorType>                      &w,
      const std::vector<std::vector<unsigned int>> *relevant) const
    {
      w.resize(subdomains_.size());
      for (const unsigned int s : owned_)
      {
        w[s].reinit(subdomains_[s]->n_dofs());
        const std::vector<Entry> &entries = rows_->entries(s);
        for (unsigned int e = 0; e < entries.size(); ++e)
          w[s](entries[e].local) +=
            entries[e].value *
            lambda[relevant ? (*relevant)[s][e] : entries[e].row];
      }
    }


    template <int dim>
    void
    TFETIDual<dim>::add_B(
      const std::vector<VectorType>                &u,
      double                                       *lambda,
      const std::vector<std::vector<unsigned int>> *relevant) const
    {
      for (const unsigned int s : owned_)
      {
        const std::vector<Entry> &entries = rows_->entries(s);
        for (unsigned int e = 0; e < entries.size(); ++e)
          lambda[relevant ? (*relevant)[s][e] : entries[e].row] +=
            entries[e].value * u[s](entries[e].local);
      }
    }


    template <int dim>
    void
    TFETIDual<dim>::apply_K_inverse(const std::vector<VectorType> &w,
                                    std::vector<VectorType>       &u) const
    {
      Timer timer;
      u.resize(subdomains_.size());
      for (const unsigned int s : owned_)
      {
        u[s].reinit(subdomains_[s]->n_dofs());
        subdomains_[s]->apply_pseudoinverse(u[s], w[s]);
      }
      ++n_stiffness_solves_;
      solve_time_ += timer.wall_time();
    }


    template <int dim>
    void
    TFETIDual<dim>::apply_F(VectorType &dst, const VectorType &src) const
    {
      apply_Bt(src.data(), work_);
      apply_K_inverse(work_, work_x_);
      dst.reinit(n_multipliers());
      add_B(work_x_, dst.data());
      sum_over_processes(dst);
    }


    template <int dim>
    void
    TFETIDual<dim>::apply_F(DistributedVector       &dst,
                            const DistributedVector &src) const
    {
      Assert(distributed_, ExcInternalError());
      const MultiplierExchange &exchange = ownership_->exchange();
      exchange.import(src, relevant_values_);
      apply_Bt(relevant_values_.data(), work_, &ownership_->relevant_index());
      apply_K_inverse(work_, work_x_);
      relevant_values_.assign(relevant_values_.size(), 0.);
      add_B(work_x_, relevant_values_.data(), &ownership_->relevant_index());
      if (dst.size() != n_multipliers())
        initialize_multipliers(dst);
      exchange.export_add(relevant_values_, dst);
    }


    template <int dim>
    void
    TFETIDual<dim>::apply_between_B(
      VectorType       &dst,
      const VectorType &src,
      const std::function<void(unsigned int, VectorType &, const VectorType &)>
        &local) const
    {
      apply_Bt(src.data(), work_);
      work_x_.resize(subdomains_.size());
      for (const unsigned int s : owned_)
      {
        work_x_[s].reinit(subdomains_[s]->n_dofs());
        local(s, work_x_[s], work_[s]);
      }
      dst.reinit(n_multipliers());
      add_B(work_x_, dst.data());
      sum_over_processes(dst);
    }


    template <int dim>
    bool
    TFETIDual<dim>::has_dirichlet_preconditioner() const
    {
      return preconditioner_ && preconditioner_->kind() ==
                                  DualPreconditioner<dim>::Kind::dirichlet;
    }


    template <int dim>
    double
    TFETIDual<dim>::preconditioner_setup_time() const
    {
      return preconditioner_setup_time_;
    }


    template <int dim>
    qp::Problem<typename TFETIDual<dim>::VectorType>
    TFETIDual<dim>::make_problem() const
    {
      qp::Problem<VectorType> problem;
      problem.hessian = [this](VectorType &dst, const VectorType &src)
      {
        apply_F(dst, src);
        dst /= scale_;
      };
      problem.b = d_;
      problem.b /= scale_;
      // the lumped (Dirichlet) preconditioner of F / s is s Q B K B' Q
      // (s Q B S B' Q): one operator for every free set, the solver zeroes
      // the active entries
      if (preconditioner_)
        problem.free_set_preconditioner = [this](const VectorType &)
        {
          return [this](VectorType &dst, const VectorType &src)
          {
            preconditioner_->vmult(dst, src);
            dst *= scale_;
          };
        };

      // the contact blocks; gluing and Dirichlet multipliers are in none:
      // free
      auto set = std::make_shared<qp::SeparableSet<VectorType>>();
      this->add_contact_blocks(*set);
      VectorType layout(n_multipliers());
      set->finalize(layout);
      problem.constraints = set;

      auto equality   = std::make_shared<qp::EqualityConstraints<VectorType>>();
      equality->vmult = [this](VectorType &dst, const VectorType &src)
      {
        coarse_->vmult(dst, src);
        coarse_->orthonormalize(dst);
      };
      equality->Tvmult = [this](VectorType &dst, const VectorType &src)
      {
        VectorType y = src;
        coarse_->orthonormalize_transpose(y);
        coarse_->Tvmult(dst, y);
      };
      equality->c = e_orthonormal_;
      describe_scaled_problem(problem,
                              *equality,
                              coarse_->n_modes(),
                              lambda_max_F_ / scale_,
                              projector_penalty_factor());
      problem.equality = equality;
      return problem;
    }


    template <int dim>
    bool
    TFETIDual<dim>::recover(const VectorType            &lambda,
                            std::vector<Vector<double>> &displacements,
                            const bool require_determined) const
    {
      AssertDimension(lambda.size(), n_multipliers());
      std::vector<VectorType> w, u;
      apply_Bt(lambda.data(), w);
      for (const unsigned int s : owned_)
        w[s].sadd(-1., 1., subdomains_[s]->load());
      apply_K_inverse(w, u);

      // alpha: G_A' alpha = -(B u - c)_A in the least-squares sense over
      // the rows that hold with equality (all but the inactive contact
      // rows)
      VectorType residual(n_multipliers());
      add_B(u, residual.data());
      sum_over_processes(residual);
      const unsigned int n_contact = this->n_contact_multipliers();
      double             scale     = 0;
      for (unsigned int i = 0; i < this->n_contact_nodes(); ++i)
        scale = std::max(scale, std::abs(lambda(i)));
      for (unsigned int r = 0; r < n_multipliers(); ++r)
        residual(r) = c_(r) - residual(r);
      VectorType alpha;
      const bool determined = coarse_->least_squares(
        [&](const unsigned int r)
        {
          return r >= n_contact ||
                 this->contact_row_is_active(lambda, r, 1e-8 * scale);
        },
        residual,
        alpha);
      AssertThrow(determined || !require_determined,
                  ExcMessage("The rigid-body motion of a floating body is "
                             "not determined: no active contact "
                             "constraint holds it."));
      const unsigned int n_rigid = dim * (dim + 1) / 2;
      for (const unsigned int s : owned_)
        for (unsigned int k = 0; k < n_rigid; ++k)
          u[s].add(alpha(s * n_rigid + k), subdomains_[s]->modes()[k]);

      // the glued field: every dof from its first copy (on the process
      // that owns that copy's subdomain, summed over the processes)
      displacements.resize(bodies_.size());
      max_jump_    = 0;
      double u_max = 0;
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        displacements[b].reinit(bodies_[b]->n_dofs());
        for (unsigned int i = 0; i < bodies_[b]->n_dofs(); ++i)
        {
          const auto [s, l] = first_copy_[b][i];
          if (owner_[s] == rank_)
            displacements[b](i) = u[s](l);
        }
        sum_over_processes(displacements[b]);
        for (unsigned int s = first_subdomain_[b]; s < first_subdomain_[b + 1];
             ++s)
          if (owner_[s] == rank_)
            for (unsigned int l = 0; l < dofs_[s].size(); ++l)
            {
              u_max = std::max(u_max, std::abs(u[s](l)));
              max_jump_ =
                std::max(max_jump_,
                         std::abs(u[s](l) - displacements[b](dofs_[s][l])));
            }
        bodies_[b]->distribute(displacements[b]);
      }
      max_jump_      = max_over_processes(max_jump_);
      u_max          = max_over_processes(u_max);
      relative_jump_ = u_max > 0 ? max_jump_ / u_max : 0.;
      return determined;
    }


    template <int dim>
    void
    TFETIDual<dim>::distribute_multipliers()
    {
      const unsigned int                     n_nodes = this->n_contact_nodes();
      std::vector<std::vector<unsigned int>> node_rows(n_nodes);
      for (unsigned int node = 0; node < n_nodes; ++node)
      {
        node_rows[node].push_back(node);
        const int j = this->frictional_index(node);
        if (j >= 0)
          for (unsigned int k = 0; k < dim - 1; ++k)
            node_rows[node].push_back(n_nodes + (dim - 1) * j + k);
      }
      ownership_ = std::make_unique<MultiplierOwnership<dim>>(
        *rows_, owner_, owned_, node_rows, communicator_);
      nodes_per_process_ = ownership_->nodes_per_process();

      d_distributed_ = std::make_unique<DistributedVector>();
      // the coarse space's vectors (n_modes() numbers) live on process 0
      owned_modes_.set_size(coarse_->n_modes());
      if (rank_ == 0)
        owned_modes_.add_range(0, coarse_->n_modes());
      e_distributed_ =
        std::make_unique<DistributedVector>(owned_modes_, communicator_);
      distribute_linear_terms();
    }


    template <int dim>
    bool
    TFETIDual<dim>::is_distributed() const
    {
      return distributed_;
    }


    template <int dim>
    void
    TFETIDual<dim>::initialize_multipliers(DistributedVector &lambda) const
    {
      Assert(distributed_, ExcInternalError());
      ownership_->layout().initialize(lambda);
    }


    template <int dim>
    void
    TFETIDual<dim>::gather(const DistributedVector &lambda,
                           VectorType              &whole) const
    {
      Assert(distributed_, ExcInternalError());
      ownership_->layout().gather(lambda, whole);
    }


    template <int dim>
    qp::Problem<typename TFETIDual<dim>::DistributedVector>
    TFETIDual<dim>::make_distributed_problem() const
    {
      AssertThrow(distributed_,
                  ExcMessage("TFETIDual: a distributed QP asked for "
                             "replicated multipliers."));
      using V = DistributedVector;
      qp::Problem<V> problem;
      problem.hessian = [this](V &dst, const V &src)
      {
        apply_F(dst, src);
        dst /= scale_;
      };
      problem.b = *d_distributed_;
      problem.b /= scale_;
      // the preconditioners act on the whole vector (their scaling
      // (B B')^{-1} is one replicated factor): gathered, applied, the owned
      // part kept
      if (preconditioner_)
        problem.free_set_preconditioner = [this](const V &)
        {
          return [this](V &dst, const V &src)
          {
            VectorType whole, result;
            gather(src, whole);
            preconditioner_->vmult(result, whole);
            result *= scale_;
            ownership_->layout().extract(result, dst);
          };
        };

      // the blocks of the owned contact nodes (a node's rows are owned
      // together)
      auto             set = std::make_shared<qp::SeparableSet<V>>();
      std::vector<int> owned_index(n_multipliers(), -1);
      for (const unsigned int r : ownership_->layout().owned_rows())
        owned_index[r] = r;
      this->add_contact_blocks(*set, owned_index);
      set->finalize(problem.b);
      problem.constraints = set;

      auto equality = std::make_shared<qp::EqualityConstraints<V>>();
      // G~ src = L^-1 P G src: the owned columns' sums over the
      // processes, on process 0
      equality->vmult = [this](V &dst, const V &src)
      {
        VectorType partial(coarse_->n_modes());
        coarse_->add_columns(partial,
                             ownership_->layout().owned_rows(),
                             src.begin());
        if (n_processes_ > 1)
        {
          // only process 0 holds the coarse vectors
          const int ierr =
            MPI_Reduce(rank_ == 0 ? MPI_IN_PLACE : partial.data(),
                       partial.data(),
                       partial.size(),
                       MPI_DOUBLE,
                       MPI_SUM,
                       0,
                       communicator_);
          AssertThrowMPI(ierr);
        }
        if (dst.size() != coarse_->n_modes())
          dst.reinit(owned_modes_, communicator_);
        if (rank_ == 0)
        {
          coarse_->orthonormalize(partial);
          for (unsigned int k = 0; k < partial.size(); ++k)
            dst.begin()[k] = partial(k);
        }
      };
      // G~' src = G' P' L^-T src: process 0's coefficients to every
      // process, then the owned columns
      equality->Tvmult = [this](V &dst, const V &src)
      {
        VectorType y(coarse_->n_modes());
        if (rank_ == 0)
        {
          for (unsigned int k = 0; k < y.size(); ++k)
            y(k) = src.begin()[k];
          coarse_->orthonormalize_transpose(y);
        }
        if (n_processes_ > 1)
        {
          const int ierr =
            MPI_Bcast(y.data(), y.size(), MPI_DOUBLE, 0, communicator_);
          AssertThrowMPI(ierr);
        }
        if (dst.size() != n_multipliers())
          initialize_multipliers(dst);
        coarse_->Tvmult_columns(y,
                                ownership_->layout().owned_rows(),
                                dst.begin());
      };
      equality->c = *e_distributed_;
      describe_scaled_problem(problem,
                              *equality,
                              coarse_->n_modes(),
                              lambda_max_F_ / scale_,
                              projector_penalty_factor());
      problem.equality = equality;
      return problem;
    }


    template <int dim>
    void
    TFETIDual<dim>::update_slip_bounds(const DistributedVector &lambda)
    {
      VectorType whole;
      gather(lambda, whole);
      this->update_slip_bounds(&whole);
    }


    template <int dim>
    bool
    TFETIDual<dim>::recover(const DistributedVector     &lambda,
                            std::vector<Vector<double>> &displacements,
                            const bool require_determined) const
    {
      VectorType whole;
      gather(lambda, whole);
      return recover(whole, displacements, require_determined);
    }


    template <int dim>
    unsigned int
    TFETIDual<dim>::n_multipliers() const
    {
      return rows_->n_rows();
    }


    template <int dim>
    unsigned int
    TFETIDual<dim>::n_rigid_body_modes() const
    {
      return coarse_->n_modes();
    }


    template <int dim>
    const std::vector<unsigned int> &
    TFETIDual<dim>::contact_nodes_per_process() const
    {
      return nodes_per_process_;
    }


    template <int dim>
    double
    TFETIDual<dim>::scale() const
    {
      return scale_;
    }


    template <int dim>
    const std::string &
    TFETIDual<dim>::operator_description() const
    {
      return operator_description_;
    }


    template <int dim>
    unsigned long
    TFETIDual<dim>::n_stiffness_solves() const
    {
      return n_stiffness_solves_;
    }


    template <int dim>
    double
    TFETIDual<dim>::stiffness_setup_time() const
    {
      return setup_time_;
    }


    template <int dim>
    double
    TFETIDual<dim>::stiffness_solve_time() const
    {
      return solve_time_;
    }


    template <int dim>
    double
    TFETIDual<dim>::assembly_time() const
    {
      return 0.;
    }


    template <int dim>
    const typename TFETIDual<dim>::VectorType &
    TFETIDual<dim>::d() const
    {
      return d_;
    }


    template class TFETIDual<2>;
    template class TFETIDual<3>;
  } // namespace decomposition
} // namespace dualcontact
