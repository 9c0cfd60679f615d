#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_templates.h>

#include <contact/dual_problem.h>
#include <fem/generalized_inverse.h>
#include <qp/power_iteration.h>
#include <qp/separable_set.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    void
    DualProblemParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Dual problem");
      prm.declare_entry(
        "Operator",
        "automatic",
        Patterns::Selection("automatic|assembled|implicit"),
        "How F = B K^# B' is applied. assembled: K is factorized with the "
        "contact dofs C ordered last, the trailing block L of the factor "
        "(S = L L', S the Schur complement of K on C) gives the dense m x m "
        "matrix F = W'W, W = L^{-1} B_C', and a product costs m^2 flops; "
        "needs `set Solver = cholmod' in `subsection Stiffness solver'. "
        "implicit: one solve with the whole factor per product. automatic: "
        "assembled when possible within the memory limit, else implicit.");
      prm.declare_entry("Memory limit",
                        "4096",
                        Patterns::Double(0),
                        "Largest memory [MB] of the scene, the one limit "
                        "of a run: before meshing, a lower-bound estimate of "
                        "the meshes and stiffness matrices of all bodies "
                        "(from subdivisions, refinements and degree) above "
                        "it stops the run; the dense matrices of the "
                        "assembled operator (F, and per body L and W) may "
                        "take this much: `automatic' falls back to implicit "
                        "above it, `assembled' stops with an error.");
      prm.declare_entry(
        "QP vectors",
        "automatic",
        Patterns::Selection("automatic|replicated|distributed"),
        "The vectors the dual QP runs on. replicated: "
        "dealii::Vector<double>, the whole QP on every process. "
        "distributed: dealii::TrilinosWrappers::MPI::Vector, the "
        "multipliers of each contact node (normal and tangential) on the "
        "process owning the node's first slave dof; F products gather what "
        "they need. automatic: distributed when run on more than one MPI "
        "process, else replicated.");
      prm.leave_subsection();
    }


    void
    DualProblemParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Dual problem");
      const std::string name = prm.get("Operator");
      form                   = name == "assembled" ? Operator::assembled :
                               name == "implicit"  ? Operator::implicit :
                                                     Operator::automatic;
      memory_limit           = prm.get_double("Memory limit");
      const std::string kind = prm.get("QP vectors");
      vectors                = kind == "replicated"  ? Vectors::replicated :
                               kind == "distributed" ? Vectors::distributed :
                                                       Vectors::automatic;
      prm.leave_subsection();
    }


    template <int dim>
    template <typename Function>
    void
    DualProblem<dim>::for_each_in_row(const unsigned int r,
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


    template <int dim>
    DualProblem<dim>::DualProblem(
      const std::vector<const fem::ElasticBody<dim> *>             &bodies,
      const ContactDiscretization<dim>                             &contact,
      const std::function<std::unique_ptr<fem::StiffnessSolver>()> &make_solver,
      const DualProblemParameters                                  &parameters)
        : DualFormulation<dim>(contact)
        , bodies_(bodies)
    {
      // The dofs of each body that B touches (C_b) and the rows of B that
      // touch it; and the memory the assembled form would take.
      const unsigned int n_bodies = bodies_.size();
      std::vector<std::vector<types::global_dof_index>> contact_dofs(n_bodies);
      std::vector<std::vector<unsigned int>>            body_rows(n_bodies);
      {
        std::vector<unsigned int> body_of_dof(contact.n_dofs());
        for (unsigned int b = 0; b < n_bodies; ++b)
          for (unsigned int i = 0; i < bodies_[b]->n_dofs(); ++i)
            body_of_dof[contact.body_offset(b) + i] = b;
        std::vector<std::vector<bool>> marked(n_bodies);
        for (unsigned int b = 0; b < n_bodies; ++b)
          marked[b].assign(bodies_[b]->n_dofs(), false);
        for (unsigned int r = 0; r < n_multipliers(); ++r)
          for_each_in_row(r,
                          [&](const types::global_dof_index column,
                              const double                  value)
                          {
                            if (value == 0.)
                              return;
                            const unsigned int b = body_of_dof[column];
                            marked[b][column - contact.body_offset(b)] = true;
                            if (body_rows[b].empty() ||
                                body_rows[b].back() != r)
                              body_rows[b].push_back(r);
                          });
        for (unsigned int b = 0; b < n_bodies; ++b)
          for (unsigned int i = 0; i < marked[b].size(); ++i)
            if (marked[b][i])
              contact_dofs[b].push_back(i);
      }
      // Peak of the assembled form: every body's L (held until F is
      // assembled), F, and one body's W and F_b at a time.
      const double m         = n_multipliers();
      double       megabytes = m * m, largest_body = 0;
      for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const double c = contact_dofs[b].size();
        const double r = body_rows[b].size();
        megabytes += c * c;
        largest_body = std::max(largest_body, c * r + r * r);
      }
      megabytes += largest_body;
      megabytes *= sizeof(double) / 1048576.;

      const unsigned int n_dofs = contact.n_dofs();
      load_.reinit(n_dofs);
      std::vector<fem::StiffnessSolver::SchurFactor> schur(n_bodies);
      bool                                           assembled =
        parameters.form != DualProblemParameters::Operator::implicit;
      for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const types::global_dof_index offset = contact.body_offset(b);
        for (unsigned int i = 0; i < bodies_[b]->n_dofs(); ++i)
          load_(offset + i) = bodies_[b]->load_vector()(i);

        modes_.push_back(
          std::make_unique<fem::RigidBodyModes<dim>>(*bodies_[b]));
        for (const auto &mode : modes_.back()->modes())
        {
          Vector<double> column(n_dofs);
          for (unsigned int i = 0; i < mode.size(); ++i)
            column(offset + i) = mode(i);
          rigid_modes_.push_back(column);
        }
        auto solver = std::make_unique<fem::GeneralizedInverse>(
          make_solver(), modes_.back()->fixing_dofs());
        if (b == 0 && assembled)
        {
          // The decision, once: every body gets the same kind of solver.
          std::ostringstream reason;
          if (!solver->offers_schur_factor())
            reason << "the stiffness solver " << solver->name()
                   << " offers no Schur factor";
          else if (megabytes > parameters.memory_limit)
            reason << std::setprecision(4) << "the dense matrices would take "
                   << megabytes << " MB, above the limit of "
                   << parameters.memory_limit << " MB";
          if (!reason.str().empty())
          {
            AssertThrow(parameters.form !=
                          DualProblemParameters::Operator::assembled,
                        ExcMessage("`set Operator = assembled' in `subsection "
                                   "Dual problem' is not possible: " +
                                   reason.str() + "."));
            assembled             = false;
            operator_description_ = "implicit (" + reason.str() + ")";
          }
        }
        if (assembled)
          solver->initialize_with_schur_factor(bodies_[b]->stiffness_matrix(),
                                               contact_dofs[b],
                                               schur[b]);
        else
          solver->initialize(bodies_[b]->stiffness_matrix());
        solvers_.push_back(std::move(solver));
      }
      if (assembled)
        assemble_operator(schur, body_rows);
      else if (operator_description_.empty())
        operator_description_ = "implicit (`set Operator = implicit')";

      // d = B K^# f - [c; -o_T]
      work_u_ = load_;
      apply_K_inverse(work_u_);
      d_.reinit(n_multipliers());
      apply_B(work_u_, d_);
      const Vector<double> c = contact.normal_bound();
      for (unsigned int i = 0; i < contact.n_nodes(); ++i)
        d_(i) -= c(i);
      for (unsigned int j = 0; j < frictional_nodes_.size(); ++j)
        for (unsigned int k = 0; k + 1 < dim; ++k)
          d_(contact.n_nodes() + (dim - 1) * j + k) +=
            contact.tangential_offset()((dim - 1) * frictional_nodes_[j] + k);

      // G = R'B' (rows B r_k), e = R'f
      e_.reinit(rigid_modes_.size());
      for (unsigned int k = 0; k < rigid_modes_.size(); ++k)
      {
        VectorType row(n_multipliers());
        apply_B(rigid_modes_[k], row);
        G_rows_.push_back(row);
        e_(k) = rigid_modes_[k] * load_;
      }

      // Orthonormal rows: G~ = L^{-1} G, e~ = L^{-1} e with G G' = L L',
      // by modified Gram-Schmidt on the rows (applied to e alike).
      G_orthonormal_ = G_rows_;
      e_orthonormal_ = e_;
      for (unsigned int k = 0; k < G_orthonormal_.size(); ++k)
      {
        for (unsigned int j = 0; j < k; ++j)
        {
          const double projection = G_orthonormal_[k] * G_orthonormal_[j];
          G_orthonormal_[k].add(-projection, G_orthonormal_[j]);
          e_orthonormal_(k) -= projection * e_orthonormal_(j);
        }
        const double norm = G_orthonormal_[k].l2_norm();
        AssertThrow(norm > 1e-10,
                    ExcMessage(
                      "A rigid-body motion of a body is not restrained by "
                      "any contact constraint (G = R'B' is rank deficient): "
                      "add a Dirichlet condition, a contact pair or "
                      "friction that holds it."));
        G_orthonormal_[k] /= norm;
        e_orthonormal_(k) /= norm;
      }

      // Scale of F for the scaled QP.
      const qp::PowerIterationResult power = qp::power_iteration<VectorType>(
        [this](VectorType &dst, const VectorType &src) { apply_F(dst, src); },
        d_,
        200,
        1e-6,
        1.0);
      scale_            = power.estimate;
      n_power_products_ = power.n_products;
      AssertThrow(scale_ > 0 && std::isfinite(scale_),
                  ExcMessage("The dual operator F = B K^# B' is zero or not "
                             "finite: are there contact constraints?"));

      distribute_multipliers(parameters);
    }


    template <int dim>
    void
    DualProblem<dim>::distribute_multipliers(
      const DualProblemParameters &parameters)
    {
      const unsigned int n_processes =
        Utilities::MPI::job_supports_mpi() ?
          Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) :
          1;
      const unsigned int m       = n_multipliers();
      const unsigned int n_nodes = contact_.n_nodes();
      AssertThrow(parameters.vectors !=
                      DualProblemParameters::Vectors::distributed ||
                    Utilities::MPI::job_supports_mpi(),
                  ExcMessage("`set QP vectors = distributed' in `subsection "
                             "Dual problem' needs MPI (Trilinos vectors), "
                             "which this program did not initialize."));
      distributed_ =
        parameters.vectors == DualProblemParameters::Vectors::distributed ||
        (parameters.vectors == DualProblemParameters::Vectors::automatic &&
         n_processes > 1);
      if (!distributed_)
      {
        // one process owns all rows, in order (recover() runs the loop of
        // the distributed recovery over them)
        owned_nodes_.resize(n_nodes);
        std::iota(owned_nodes_.begin(), owned_nodes_.end(), 0u);
        owned_frictional_.resize(frictional_nodes_.size());
        std::iota(owned_frictional_.begin(), owned_frictional_.end(), 0u);
        owned_rows_.resize(m);
        std::iota(owned_rows_.begin(), owned_rows_.end(), 0u);
        owned_multipliers_ = complete_index_set(m);
        nodes_per_process_.assign(1, n_nodes);
        multipliers_per_process_.assign(1, m);
        return;
      }
      communicator_           = MPI_COMM_WORLD;
      const unsigned int rank = Utilities::MPI::this_mpi_process(communicator_);

      // a node belongs to the process owning its first slave dof, if the
      // bodies are partitioned (every node claimed exactly once); else
      // (bodies on plain triangulations: every process owns all dofs) the
      // nodes are split evenly in their order
      std::vector<unsigned int> mine(n_nodes, 0), claims(n_nodes, 0);
      for (unsigned int i = 0; i < n_nodes; ++i)
      {
        const ContactNode<dim> &node = contact_.nodes()[i];
        const unsigned int      b    = contact_.pairs()[node.pair].slave_body;
        mine[i] = bodies_[b]->dof_handler().locally_owned_dofs().is_element(
                    node.dofs[0]) ?
                    1 :
                    0;
      }
      Utilities::MPI::sum(mine, communicator_, claims);
      const bool partitioned =
        std::all_of(claims.begin(),
                    claims.end(),
                    [](const unsigned int c) { return c == 1; });
      owned_nodes_.clear();
      owned_frictional_.clear();
      for (unsigned int i = 0; i < n_nodes; ++i)
      {
        const bool owned =
          partitioned ?
            mine[i] == 1 :
            (i >= static_cast<unsigned long>(n_nodes) * rank / n_processes &&
             i <
               static_cast<unsigned long>(n_nodes) * (rank + 1) / n_processes);
        if (!owned)
          continue;
        owned_nodes_.push_back(i);
        if (frictional_index_[i] >= 0)
          owned_frictional_.push_back(frictional_index_[i]);
      }

      owned_multipliers_ = IndexSet(m);
      for (const unsigned int i : owned_nodes_)
        owned_multipliers_.add_index(i);
      for (const unsigned int j : owned_frictional_)
        owned_multipliers_.add_range(n_nodes + (dim - 1) * j,
                                     n_nodes + (dim - 1) * (j + 1));
      owned_multipliers_.compress();
      owned_rows_.clear();
      for (const auto r : owned_multipliers_)
        owned_rows_.push_back(r);
      nodes_per_process_ = Utilities::MPI::all_gather(
        communicator_, static_cast<unsigned int>(owned_nodes_.size()));
      multipliers_per_process_ = Utilities::MPI::all_gather(
        communicator_, static_cast<unsigned int>(owned_rows_.size()));

      d_distributed_ = std::make_unique<DistributedVector>();
      initialize_multipliers(*d_distributed_);
      for (unsigned int k = 0; k < owned_rows_.size(); ++k)
        d_distributed_->begin()[k] = d_(owned_rows_[k]);

      // the few rows of G and e: on process 0
      const unsigned int n_modes = rigid_modes_.size();
      owned_modes_               = IndexSet(n_modes);
      if (rank == 0)
        owned_modes_.add_range(0, n_modes);
      owned_modes_.compress();
      e_distributed_ = std::make_unique<DistributedVector>();
      e_distributed_->reinit(owned_modes_, communicator_);
      for (unsigned int k = 0; k < e_distributed_->locally_owned_size(); ++k)
        e_distributed_->begin()[k] =
          e_orthonormal_(owned_modes_.nth_index_in_set(k));
    }


    template <int dim>
    bool
    DualProblem<dim>::is_distributed() const
    {
      return distributed_;
    }


    template <int dim>
    const IndexSet &
    DualProblem<dim>::locally_owned_multipliers() const
    {
      return owned_multipliers_;
    }


    template <int dim>
    const std::vector<unsigned int> &
    DualProblem<dim>::contact_nodes_per_process() const
    {
      return nodes_per_process_;
    }


    template <int dim>
    const std::vector<unsigned int> &
    DualProblem<dim>::multipliers_per_process() const
    {
      return multipliers_per_process_;
    }


    template <int dim>
    void
    DualProblem<dim>::initialize_multipliers(DistributedVector &lambda) const
    {
      AssertThrow(distributed_,
                  ExcMessage("DualProblem: distributed multipliers asked "
                             "for a replicated dual problem."));
      lambda.reinit(owned_multipliers_, communicator_);
    }


    template <int dim>
    void
    DualProblem<dim>::gather(const DistributedVector &lambda,
                             VectorType              &whole) const
    {
      AssertDimension(lambda.locally_owned_size(), owned_rows_.size());
      whole.reinit(n_multipliers());
      for (unsigned int k = 0; k < owned_rows_.size(); ++k)
        whole(owned_rows_[k]) = lambda.begin()[k];
      // each entry is owned by one process: the sum is the entry itself
      const int ierr = MPI_Allreduce(MPI_IN_PLACE,
                                     whole.begin(),
                                     whole.size(),
                                     MPI_DOUBLE,
                                     MPI_SUM,
                                     communicator_);
      AssertThrowMPI(ierr);
    }


    template <int dim>
    DualProblem<dim>::~DualProblem() = default;


    template <int dim>
    unsigned int
    DualProblem<dim>::n_multipliers() const
    {
      return contact_.n_nodes() + (dim - 1) * frictional_nodes_.size();
    }

    template <int dim>
    unsigned int
    DualProblem<dim>::n_rigid_body_modes() const
    {
      return rigid_modes_.size();
    }


    template <int dim>
    void
    DualProblem<dim>::update_slip_bounds(const DistributedVector &lambda)
    {
      Assert(distributed_, ExcInternalError());
      // the owned nodes' bounds, zero elsewhere, summed: each node's bound
      // comes from the one process that owns it
      const unsigned int  n_frictional = frictional_nodes_.size();
      std::vector<double> first(n_frictional, 0.), second(n_frictional, 0.);
      for (const unsigned int j : owned_frictional_)
      {
        const unsigned int      node = frictional_nodes_[j];
        const ContactNode<dim> &n    = contact_.nodes()[node];
        const FrictionLaw      &law  = contact_.pairs()[n.pair].friction;
        if (law.is_coulomb())
        {
          const double lambda_n =
            std::max(lambda.begin()[owned_multipliers_.index_within_set(node)],
                     0.);
          first[j] = law.first * lambda_n;
          second[j] =
            (law.is_orthotropic() ? law.second : law.first) * lambda_n;
        }
        else
        {
          first[j] = law.first * n.weight;
          second[j] =
            (law.is_orthotropic() ? law.second : law.first) * n.weight;
        }
      }
      Utilities::MPI::sum(first, communicator_, psi_first_);
      Utilities::MPI::sum(second, communicator_, psi_second_);
    }


    template <int dim>
    qp::Problem<typename DualProblem<dim>::VectorType>
    DualProblem<dim>::make_problem() const
    {
      qp::Problem<VectorType> problem;
      problem.hessian = [this](VectorType &dst, const VectorType &src)
      {
        apply_F(dst, src);
        dst /= scale_;
      };
      problem.b = d_;
      problem.b /= scale_;
      // the power iteration's estimate approaches from below
      problem.lambda_max = 1.05;
      // F = B K^+ B' is dense: `auto' keeps the given parameters
      // (SolverChain::attempt_parameters)
      problem.hessian_storage = qp::HessianStorage::dense_matrix;

      auto set = std::make_shared<qp::SeparableSet<VectorType>>();
      this->add_contact_blocks(*set);
      VectorType layout(n_multipliers());
      set->finalize(layout);
      problem.constraints = set;

      if (!G_rows_.empty())
      {
        auto equality = std::make_shared<qp::EqualityConstraints<VectorType>>();
        equality->vmult = [this](VectorType &dst, const VectorType &src)
        {
          dst.reinit(G_orthonormal_.size());
          for (unsigned int k = 0; k < G_orthonormal_.size(); ++k)
            dst(k) = G_orthonormal_[k] * src;
        };
        equality->Tvmult = [this](VectorType &dst, const VectorType &src)
        {
          dst.reinit(n_multipliers());
          for (unsigned int k = 0; k < G_orthonormal_.size(); ++k)
            dst.add(src(k), G_orthonormal_[k]);
        };
        equality->c             = e_orthonormal_;
        equality->n_constraints = G_orthonormal_.size();
        equality->norm_sq       = 1.; // ||G~||^2 = lambda_max(G~ G~') = 1
        problem.equality        = equality;
        problem.semidefinite    = true;
      }
      return problem;
    }


    template <int dim>
    qp::Problem<typename DualProblem<dim>::DistributedVector>
    DualProblem<dim>::make_distributed_problem() const
    {
      AssertThrow(distributed_,
                  ExcMessage("DualProblem: a distributed QP asked for a "
                             "replicated dual problem."));
      using V = DistributedVector;
      qp::Problem<V> problem;
      problem.hessian = [this](V &dst, const V &src)
      {
        apply_F(dst, src);
        dst /= scale_;
      };
      problem.b = *d_distributed_;
      problem.b /= scale_;
      problem.lambda_max      = 1.05;
      problem.hessian_storage = qp::HessianStorage::dense_matrix;

      // the blocks of the owned nodes only (the same as make_problem()'s)
      auto               set     = std::make_shared<qp::SeparableSet<V>>();
      const unsigned int n_nodes = contact_.n_nodes();
      for (const unsigned int i : owned_nodes_)
        set->add_bound(i, 0.);
      for (const unsigned int j : owned_frictional_)
      {
        const unsigned int first = n_nodes + (dim - 1) * j;
        const FrictionLaw &law =
          contact_.pairs()[contact_.nodes()[frictional_nodes_[j]].pair]
            .friction;
        if (std::isinf(psi_first_[j]) || std::isinf(psi_second_[j]))
          continue;
        if (dim == 2)
          set->add_box(first, -psi_first_[j], psi_first_[j]);
        else if (law.is_orthotropic() && psi_first_[j] > 0 &&
                 psi_second_[j] > 0)
          set->add_ellipse(first, psi_first_[j], psi_second_[j]);
        else
          set->add_disc(first, std::min(psi_first_[j], psi_second_[j]));
      }
      set->finalize(problem.b);
      problem.constraints = set;

      if (!G_rows_.empty())
      {
        auto equality = std::make_shared<qp::EqualityConstraints<V>>();
        // dst = G~ src: partial dot products over the owned multipliers,
        // summed; the rows live on process 0
        equality->vmult = [this](V &dst, const V &src)
        {
          const unsigned int  n_modes = G_orthonormal_.size();
          std::vector<double> partial(n_modes, 0.), total(n_modes);
          for (unsigned int k = 0; k < n_modes; ++k)
            for (unsigned int l = 0; l < owned_rows_.size(); ++l)
              partial[k] += G_orthonormal_[k](owned_rows_[l]) * src.begin()[l];
          Utilities::MPI::sum(partial, communicator_, total);
          if (dst.size() != n_modes)
            dst.reinit(owned_modes_, communicator_);
          for (unsigned int l = 0; l < dst.locally_owned_size(); ++l)
            dst.begin()[l] = total[owned_modes_.nth_index_in_set(l)];
        };
        // dst = G~' src: the few coefficients to every process, then the
        // owned entries
        equality->Tvmult = [this](V &dst, const V &src)
        {
          const unsigned int  n_modes = G_orthonormal_.size();
          std::vector<double> partial(n_modes, 0.), total(n_modes);
          for (unsigned int l = 0; l < src.locally_owned_size(); ++l)
            partial[owned_modes_.nth_index_in_set(l)] = src.begin()[l];
          Utilities::MPI::sum(partial, communicator_, total);
          if (dst.size() != n_multipliers())
            initialize_multipliers(dst);
          for (unsigned int l = 0; l < owned_rows_.size(); ++l)
          {
            double value = 0;
            for (unsigned int k = 0; k < n_modes; ++k)
              value += total[k] * G_orthonormal_[k](owned_rows_[l]);
            dst.begin()[l] = value;
          }
        };
        equality->c             = *e_distributed_;
        equality->n_constraints = G_orthonormal_.size();
        equality->norm_sq       = 1.;
        problem.equality        = equality;
        problem.semidefinite    = true;
      }
      return problem;
    }


    template <int dim>
    void
    DualProblem<dim>::apply_F(DistributedVector       &dst,
                              const DistributedVector &src) const
    {
      Assert(distributed_, ExcInternalError());
      if (dst.size() != n_multipliers())
        initialize_multipliers(dst);
      if (is_assembled())
      {
        // the whole src, then the owned rows of F (= columns, F is
        // symmetric and column-major) by runs of consecutive rows
        gather(src, work_lambda_);
        const types::blas_int m = n_multipliers(), one = 1;
        const double          alpha = 1., beta = 0.;
        for (unsigned int k = 0; k < owned_rows_.size();)
        {
          unsigned int end = k + 1;
          while (end < owned_rows_.size() &&
                 owned_rows_[end] == owned_rows_[end - 1] + 1)
            ++end;
          const types::blas_int n_rows = end - k;
          gemv("T",
               &m,
               &n_rows,
               &alpha,
               F_dense_.data() + static_cast<std::size_t>(owned_rows_[k]) * m,
               &m,
               work_lambda_.begin(),
               &one,
               &beta,
               dst.begin() + k,
               &one);
          k = end;
        }
        return;
      }
      Vector<double> u;
      apply_Bt_distributed(src, u);
      apply_K_inverse(u);
      for (unsigned int k = 0; k < owned_rows_.size(); ++k)
        dst.begin()[k] = row_times(owned_rows_[k], u);
    }


    template <int dim>
    void
    DualProblem<dim>::apply_Bt_distributed(const DistributedVector &lambda,
                                           Vector<double>          &u) const
    {
      u.reinit(contact_.n_dofs());
      for (unsigned int k = 0; k < owned_rows_.size(); ++k)
      {
        const double value = lambda.begin()[k];
        if (value != 0.)
          for_each_in_row(owned_rows_[k],
                          [&](const types::global_dof_index column,
                              const double                  entry)
                          { u(column) += entry * value; });
      }
      const int ierr = MPI_Allreduce(
        MPI_IN_PLACE, u.begin(), u.size(), MPI_DOUBLE, MPI_SUM, communicator_);
      AssertThrowMPI(ierr);
    }


    template <int dim>
    double
    DualProblem<dim>::row_times(const unsigned int    r,
                                const Vector<double> &u) const
    {
      double value = 0;
      for_each_in_row(r,
                      [&](const types::global_dof_index column,
                          const double entry) { value += entry * u(column); });
      return value;
    }


    template <int dim>
    void
    DualProblem<dim>::apply_K_inverse(Vector<double> &x) const
    {
      Vector<double> in, out;
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        const types::global_dof_index offset = contact_.body_offset(b);
        const unsigned int            n      = bodies_[b]->n_dofs();
        in.reinit(n, true);
        for (unsigned int i = 0; i < n; ++i)
          in(i) = x(offset + i);
        solvers_[b]->solve(out, in);
        for (unsigned int i = 0; i < n; ++i)
          x(offset + i) = out(i);
      }
      ++n_stiffness_solves_;
    }


    template <int dim>
    void
    DualProblem<dim>::apply_B(const Vector<double> &u, VectorType &lambda) const
    {
      const unsigned int n_nodes = contact_.n_nodes();
      lambda.reinit(n_multipliers(), true);
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
    DualProblem<dim>::apply_Bt(const VectorType &lambda,
                               Vector<double>   &u) const
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
    DualProblem<dim>::assemble_operator(
      std::vector<fem::StiffnessSolver::SchurFactor> &schur,
      const std::vector<std::vector<unsigned int>>   &rows)
    {
      Timer                 timer;
      const types::blas_int m = n_multipliers();
      F_dense_.assign(static_cast<std::size_t>(m) * m, 0.);
      std::vector<double>       W, Fb;
      std::ostringstream        sizes;
      std::vector<unsigned int> local_index;
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        const types::blas_int c = schur[b].dofs.size();
        const types::blas_int r = rows[b].size();
        sizes << (b == 0 ? "" : ", ") << c;
        if (c == 0 || r == 0)
          continue;
        // W = (B_b)_C' as a dense c x r matrix, then W = L^{-1} W.
        const types::global_dof_index offset = contact_.body_offset(b);
        local_index.assign(bodies_[b]->n_dofs(), numbers::invalid_unsigned_int);
        for (types::blas_int k = 0; k < c; ++k)
          local_index[schur[b].dofs[k]] = k;
        W.assign(static_cast<std::size_t>(c) * r, 0.);
        for (types::blas_int q = 0; q < r; ++q)
          for_each_in_row(rows[b][q],
                          [&](const types::global_dof_index column,
                              const double                  value)
                          {
                            if (column < offset ||
                                column >= offset + bodies_[b]->n_dofs())
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
      operator_description_ = line.str();
    }


    template <int dim>
    double
    DualProblem<dim>::stiffness_setup_time() const
    {
      double time = 0;
      for (const auto &solver : solvers_)
        time += solver->statistics().setup_time;
      return time;
    }


    template <int dim>
    double
    DualProblem<dim>::stiffness_solve_time() const
    {
      double time = 0;
      for (const auto &solver : solvers_)
        time += solver->statistics().solve_time;
      return time;
    }


    template <int dim>
    bool
    DualProblem<dim>::is_assembled() const
    {
      return !F_dense_.empty();
    }


    template <int dim>
    const std::string &
    DualProblem<dim>::operator_description() const
    {
      return operator_description_;
    }


    template <int dim>
    double
    DualProblem<dim>::assembly_time() const
    {
      return assembly_time_;
    }


    template <int dim>
    void
    DualProblem<dim>::apply_F(VectorType &dst, const VectorType &src) const
    {
      if (is_assembled())
      {
        const types::blas_int m = n_multipliers(), one = 1;
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
        return;
      }
      Vector<double> u;
      apply_Bt(src, u);
      apply_K_inverse(u);
      apply_B(u, dst);
    }


    template <int dim>
    const typename DualProblem<dim>::VectorType &
    DualProblem<dim>::d() const
    {
      return d_;
    }


    template <int dim>
    bool
    DualProblem<dim>::recover(const VectorType            &lambda,
                              std::vector<Vector<double>> &displacements,
                              const bool require_determined) const
    {
      if (distributed_)
      {
        DistributedVector owned;
        initialize_multipliers(owned);
        for (unsigned int k = 0; k < owned_rows_.size(); ++k)
          owned.begin()[k] = lambda(owned_rows_[k]);
        return recover(owned, displacements, require_determined);
      }
      Vector<double> u;
      apply_Bt(lambda, u);
      return finish_recovery(lambda.begin(),
                             u,
                             displacements,
                             require_determined);
    }


    template <int dim>
    bool
    DualProblem<dim>::recover(const DistributedVector     &lambda,
                              std::vector<Vector<double>> &displacements,
                              const bool require_determined) const
    {
      Assert(distributed_, ExcInternalError());
      Vector<double> u;
      apply_Bt_distributed(lambda, u);
      return finish_recovery(lambda.begin(),
                             u,
                             displacements,
                             require_determined);
    }


    template <int dim>
    bool
    DualProblem<dim>::finish_recovery(
      const double                *lambda,
      Vector<double>              &u,
      std::vector<Vector<double>> &displacements,
      const bool                   require_determined) const
    {
      u.sadd(-1., 1., load_);
      apply_K_inverse(u);
      if (rigid_modes_.empty())
      {
        split_displacements(u, displacements);
        return true;
      }
      // The owned multipliers (replicated: all) in local order: the owned
      // normal multipliers first, then the owned tangential ones, node by
      // node.  Rows that must hold with equality: normal rows with a
      // positive multiplier, and the tangential rows of sticking nodes
      // (multiplier strictly inside a nonzero friction set).  A Tresca
      // bound acts whether or not the node is pressed, so a separated node
      // can stick; a zero bound (Coulomb without normal force) constrains
      // nothing.
      const unsigned int n_nodes = contact_.n_nodes();
      const unsigned int n_owned = owned_nodes_.size();
      double             scale   = 0;
      for (unsigned int q = 0; q < n_owned; ++q)
        scale = std::max(scale, std::abs(lambda[q]));
      scale                 = Utilities::MPI::max(scale, communicator_);
      const double      tol = 1e-8 * scale;
      std::vector<bool> active(owned_rows_.size(), false);
      for (unsigned int q = 0; q < n_owned; ++q)
        active[q] = lambda[q] > tol;
      for (unsigned int p = 0; p < owned_frictional_.size(); ++p)
      {
        const unsigned int j     = owned_frictional_[p];
        const unsigned int first = n_owned + (dim - 1) * p;
        if (std::max(psi_first_[j], psi_second_[j]) > 0 &&
            friction_utilization(j, lambda + first) < 1 - 1e-6)
          for (unsigned int k = 0; k + 1 < dim; ++k)
            active[first + k] = true;
      }
      // alpha = (G_A G_A')^{-1} G_A (-r_A): G_A' alpha = -r_A in the
      // least-squares sense, r the residual of the constraints without
      // the rigid motion, r = B u - [c; -o_T] (= d - F lambda)
      const Vector<double> c = contact_.normal_bound();
      const unsigned int   m = rigid_modes_.size();
      // GGt and rhs in one buffer, summed over the processes
      std::vector<double> sums(m * m + m, 0.), total(m * m + m);
      for (unsigned int l = 0; l < owned_rows_.size(); ++l)
      {
        if (!active[l])
          continue;
        const unsigned int r        = owned_rows_[l];
        double             residual = row_times(r, u);
        if (r < n_nodes)
          residual -= c(r);
        else
          residual += contact_.tangential_offset()(
            (dim - 1) * frictional_nodes_[(r - n_nodes) / (dim - 1)] +
            (r - n_nodes) % (dim - 1));
        for (unsigned int k = 0; k < m; ++k)
        {
          sums[m * m + k] -= G_rows_[k](r) * residual;
          for (unsigned int l2 = 0; l2 < m; ++l2)
            sums[k * m + l2] += G_rows_[k](r) * G_rows_[l2](r);
        }
      }
      Utilities::MPI::sum(sums, communicator_, total);
      FullMatrix<double> GGt(m, m);
      Vector<double>     rhs(m);
      for (unsigned int k = 0; k < m; ++k)
      {
        rhs(k) = total[m * m + k];
        for (unsigned int l2 = 0; l2 < m; ++l2)
          GGt(k, l2) = total[k * m + l2];
      }
      const bool determined = add_rigid_motion(GGt, rhs, u, require_determined);
      split_displacements(u, displacements);
      return determined;
    }


    template <int dim>
    bool
    DualProblem<dim>::add_rigid_motion(FullMatrix<double>   &GGt,
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


    template <int dim>
    void
    DualProblem<dim>::split_displacements(
      const Vector<double>        &u,
      std::vector<Vector<double>> &displacements) const
    {
      displacements.resize(bodies_.size());
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        const types::global_dof_index offset = contact_.body_offset(b);
        displacements[b].reinit(bodies_[b]->n_dofs());
        for (unsigned int i = 0; i < bodies_[b]->n_dofs(); ++i)
          displacements[b](i) = u(offset + i);
        bodies_[b]->distribute(displacements[b]);
      }
    }


    template <int dim>
    double
    DualProblem<dim>::scale() const
    {
      return scale_;
    }


    template <int dim>
    unsigned long
    DualProblem<dim>::n_stiffness_solves() const
    {
      return n_stiffness_solves_;
    }


    template class DualProblem<2>;
    template class DualProblem<3>;
  } // namespace contact
} // namespace dualcontact
