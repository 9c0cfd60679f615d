#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_templates.h>

#include <contact/assembled_dual_operator.h>
#include <contact/dual_problem.h>
#include <contact/implicit_dual_operator.h>
#include <fem/generalized_inverse.h>
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
        "process owning the node's first slave dof (TFETI: every row of B, "
        "gluing and Dirichlet ones too, on the process of a subdomain it "
        "touches); F products gather what they need. The "
        "working set (`subsection Working set') runs on replicated vectors "
        "only. automatic: distributed on more than one MPI process under "
        "TFETI or with a distributed stiffness solver (mumps, amg); "
        "replicated otherwise (one process, or cholmod / umfpack, which "
        "factorize the whole matrix on every process).");
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
    DualProblem<dim>::DualProblem(
      const std::vector<const fem::ElasticBody<dim> *>             &bodies,
      const ContactDiscretization<dim>                             &contact,
      const std::function<std::unique_ptr<fem::StiffnessSolver>()> &make_solver,
      const DualProblemParameters                                  &parameters)
        : DualFormulation<dim>(contact)
        , bodies_(bodies)
        , rows_(contact, frictional_nodes_)
        , inverse_(bodies, contact)
        , rigid_body_fit_(contact,
                          rows_,
                          frictional_nodes_,
                          rigid_modes_,
                          G_rows_)
    {
      // The dofs of each body that B touches (C_b) and the rows of B that
      // touch it; and the memory the assembled form would take.
      const unsigned int n_bodies = bodies_.size();
      std::vector<std::vector<types::global_dof_index>> contact_dofs(n_bodies);
      std::vector<std::vector<unsigned int>>            body_rows(n_bodies);
      {
        std::vector<std::vector<bool>> marked(n_bodies);
        for (unsigned int b = 0; b < n_bodies; ++b)
          marked[b].assign(bodies_[b]->n_dofs(), false);
        for (unsigned int r = 0; r < n_multipliers(); ++r)
          rows_.for_each_in_row(
            r,
            [&](const types::global_dof_index column, const double value)
            {
              if (value == 0.)
                return;
              const unsigned int b = contact.body_of_dof(column);
              marked[b][column - contact.body_offset(b)] = true;
              if (body_rows[b].empty() || body_rows[b].back() != r)
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
      std::string implicit_description = "implicit (`set Operator = implicit')";
      std::vector<const fem::GeneralizedInverse *> pseudoinverses(n_bodies);
      std::vector<unsigned int>                    first_mode(n_bodies);
      for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const types::global_dof_index offset = contact.body_offset(b);
        for (unsigned int i = 0; i < bodies_[b]->n_dofs(); ++i)
          load_(offset + i) = bodies_[b]->load_vector()(i);

        modes_.push_back(
          std::make_unique<fem::RigidBodyModes<dim>>(*bodies_[b]));
        first_mode[b] = rigid_modes_.size();
        for (const auto &mode : modes_.back()->modes())
        {
          Vector<double> column(n_dofs);
          for (unsigned int i = 0; i < mode.size(); ++i)
            column(offset + i) = mode(i);
          rigid_modes_.push_back(column);
        }
        auto solver = std::make_unique<fem::GeneralizedInverse>(
          make_solver(), modes_.back()->fixing_dofs(), modes_.back()->modes());
        pseudoinverses[b] = solver.get();
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
            assembled            = false;
            implicit_description = "implicit (" + reason.str() + ")";
          }
        }
        if (assembled)
          solver->initialize_with_schur_factor(bodies_[b]->stiffness_matrix(),
                                               contact_dofs[b],
                                               schur[b]);
        else
          solver->initialize(bodies_[b]->stiffness_matrix());
        inverse_.add(std::move(solver));
      }
      // G = R'B' (rows B r_k), e = R'f
      e_.reinit(rigid_modes_.size());
      for (unsigned int k = 0; k < rigid_modes_.size(); ++k)
      {
        VectorType row(n_multipliers());
        rows_.vmult(row, rigid_modes_[k]);
        G_rows_.push_back(row);
        e_(k) = rigid_modes_[k] * load_;
      }

      if (assembled)
      {
        auto F = std::make_unique<AssembledDualOperator<dim>>(
          bodies_, contact, rows_, schur, body_rows);
        for (unsigned int b = 0; b < n_bodies; ++b)
          if (!pseudoinverses[b]->kernel().empty())
            add_pseudoinverse_terms(
              b, first_mode[b], *pseudoinverses[b], body_rows[b], *F);
        operator_ = std::move(F);
      }
      else
        operator_ =
          std::make_unique<ImplicitDualOperator<dim>>(rows_,
                                                      inverse_,
                                                      implicit_description);

      form_linear_term();

      // The transforms of the QP the solvers see: G with orthonormal rows,
      // and the scale of F.
      equalities_ = std::make_unique<OrthonormalEqualities>(G_rows_, e_);
      scaling_    = std::make_unique<LambdaMaxScaling>(
        [this](VectorType &dst, const VectorType &src) { apply_F(dst, src); },
        d_);

      distribute_multipliers(parameters);
    }


    template <int dim>
    void
    DualProblem<dim>::form_linear_term()
    {
      // d = B K^+ f - [c; s - o_T], s the slip of the previous load step
      // (design.md, "Load history"; zero for the static problem)
      Vector<double> u = load_;
      inverse_.apply(u);
      d_.reinit(n_multipliers());
      rows_.vmult(d_, u);
      const Vector<double> c = contact_.normal_bound();
      for (unsigned int i = 0; i < contact_.n_nodes(); ++i)
        d_(i) -= c(i);
      for (unsigned int j = 0; j < frictional_nodes_.size(); ++j)
        for (unsigned int k = 0; k + 1 < dim; ++k)
        {
          const unsigned int t = (dim - 1) * frictional_nodes_[j] + k;
          d_(contact_.n_nodes() + (dim - 1) * j + k) +=
            contact_.tangential_offset()(t) -
            (previous_slip_.size() > 0 ? previous_slip_(t) : 0.);
        }
    }


    template <int dim>
    void
    DualProblem<dim>::update_load(const Vector<double> &previous_slip)
    {
      Assert(previous_slip.size() == 0 ||
               previous_slip.size() == (dim - 1) * contact_.n_nodes(),
             ExcDimensionMismatch(previous_slip.size(),
                                  (dim - 1) * contact_.n_nodes()));
      previous_slip_ = previous_slip;
      rigid_body_fit_.set_previous_slip(&previous_slip_);
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        const types::global_dof_index offset = contact_.body_offset(b);
        for (unsigned int i = 0; i < bodies_[b]->n_dofs(); ++i)
          load_(offset + i) = bodies_[b]->load_vector()(i);
      }
      for (unsigned int k = 0; k < rigid_modes_.size(); ++k)
        e_(k) = rigid_modes_[k] * load_;
      equalities_ = std::make_unique<OrthonormalEqualities>(G_rows_, e_);
      form_linear_term();
      // F, its factorizations and its scale are those of the construction
      if (is_distributed())
      {
        const std::vector<unsigned int> &owned_rows =
          distribution_->owned_rows();
        for (unsigned int k = 0; k < owned_rows.size(); ++k)
          d_distributed_->begin()[k] = d_(owned_rows[k]);
        equalities_->distribute(*distribution_);
      }
    }


    template <int dim>
    double
    DualProblem<dim>::projector_penalty_factor() const
    {
      // Measured on the floating scenes (products at factor 1 / 3 / 10;
      // lib/contact/README.md, "Pseudoinverses"): bounds and boxes want
      // rho well above lambda_max(P F P), whose few large eigenvalues the
      // inner solvers' conjugate gradient steps absorb (3D Hertz 274 / 176
      // / 140, the Tresca block 316 / 207 / 158); friction discs and
      // ellipses want it at lambda_max(P F P), whose inner solves are
      // projection steps that rho shortens (the Coulomb block 1,864 /
      // 3,589 / 8,602).
      const bool discs = dim == 3 && !frictional_nodes_.empty();
      return discs ? 1. : 10.;
    }


    template <int dim>
    void
    DualProblem<dim>::add_pseudoinverse_terms(
      const unsigned int               body,
      const unsigned int               first_mode,
      const fem::GeneralizedInverse   &inverse,
      const std::vector<unsigned int> &rows,
      AssembledDualOperator<dim>      &F) const
    {
      const std::vector<Vector<double>> &R = inverse.kernel();
      const unsigned int                 k = R.size(), r = rows.size();
      const types::global_dof_index      offset = contact_.body_offset(body);
      // W = B K^# R, G = R'B' (G_rows_ on the body's rows), C = R'K^#R
      FullMatrix<double> W(r, k), G(k, r), C(k, k);
      Vector<double>     stacked(contact_.n_dofs()), image,
        row_values(n_multipliers());
      for (unsigned int j = 0; j < k; ++j)
      {
        image.reinit(R[j].size());
        inverse.solve_fixing_dofs(image, R[j]);
        for (unsigned int i = 0; i < k; ++i)
          C(i, j) = R[i] * image;
        for (unsigned int i = 0; i < image.size(); ++i)
          stacked(offset + i) = image(i);
        rows_.vmult(row_values, stacked);
        for (unsigned int q = 0; q < r; ++q)
        {
          W(q, j) = row_values(rows[q]);
          G(j, q) = G_rows_[first_mode + j](rows[q]);
        }
      }
      // X = W - G'C / 2, so that W G + G'W' - G'C G = X G + G'X'
      for (unsigned int q = 0; q < r; ++q)
        for (unsigned int j = 0; j < k; ++j)
          for (unsigned int i = 0; i < k; ++i)
            W(q, j) -= 0.5 * G(i, q) * C(i, j);
      F.subtract_symmetric_update(rows, W, G);
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
      AssertThrow(parameters.vectors !=
                      DualProblemParameters::Vectors::distributed ||
                    Utilities::MPI::job_supports_mpi(),
                  ExcMessage("`set QP vectors = distributed' in `subsection "
                             "Dual problem' needs MPI (Trilinos vectors), "
                             "which this program did not initialize."));
      // automatic: distributed where the solves are (MUMPS, AMG); with a
      // serial solver every process holds the whole factor, and the QP on
      // replicated vectors is the one-process run, working set included
      const bool distributed =
        parameters.vectors == DualProblemParameters::Vectors::distributed ||
        (parameters.vectors == DualProblemParameters::Vectors::automatic &&
         n_processes > 1 && inverse_.is_distributed());
      distribution_ = std::make_unique<MultiplierDistribution>(
        bodies_, contact_, frictional_nodes_, frictional_index_, distributed);
      if (!distributed)
        return;

      const std::vector<unsigned int> &owned_rows = distribution_->owned_rows();
      d_distributed_ = std::make_unique<DistributedVector>();
      initialize_multipliers(*d_distributed_);
      for (unsigned int k = 0; k < owned_rows.size(); ++k)
        d_distributed_->begin()[k] = d_(owned_rows[k]);
      // the few rows of G and e: on process 0
      equalities_->distribute(*distribution_);
    }


    template <int dim>
    bool
    DualProblem<dim>::is_distributed() const
    {
      return distribution_->is_distributed();
    }


    template <int dim>
    const IndexSet &
    DualProblem<dim>::locally_owned_multipliers() const
    {
      return distribution_->layout().locally_owned();
    }


    template <int dim>
    const std::vector<unsigned int> &
    DualProblem<dim>::contact_nodes_per_process() const
    {
      return distribution_->nodes_per_process();
    }


    template <int dim>
    const std::vector<unsigned int> &
    DualProblem<dim>::multipliers_per_process() const
    {
      return distribution_->multipliers_per_process();
    }


    template <int dim>
    void
    DualProblem<dim>::initialize_multipliers(DistributedVector &lambda) const
    {
      AssertThrow(distribution_->is_distributed(),
                  ExcMessage("DualProblem: distributed multipliers asked "
                             "for a replicated dual problem."));
      distribution_->layout().initialize(lambda);
    }


    template <int dim>
    void
    DualProblem<dim>::gather(const DistributedVector &lambda,
                             VectorType              &whole) const
    {
      distribution_->layout().gather(lambda, whole);
    }


    template <int dim>
    DualProblem<dim>::~DualProblem() = default;


    template <int dim>
    unsigned int
    DualProblem<dim>::n_multipliers() const
    {
      return this->n_contact_multipliers();
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
      Assert(is_distributed(), ExcInternalError());
      // the owned nodes' bounds, zero elsewhere, summed: each node's bound
      // comes from the one process that owns it
      const unsigned int  n_frictional = frictional_nodes_.size();
      std::vector<double> first(n_frictional, 0.), second(n_frictional, 0.);
      const IndexSet     &owned = distribution_->layout().locally_owned();
      for (const unsigned int j : distribution_->owned_frictional())
      {
        const unsigned int      node = frictional_nodes_[j];
        const ContactNode<dim> &n    = contact_.nodes()[node];
        const FrictionLaw      &law  = contact_.pairs()[n.pair].friction;
        if (law.is_coulomb())
        {
          const double lambda_n =
            std::max(lambda.begin()[owned.index_within_set(node)], 0.);
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
      Utilities::MPI::sum(first, distribution_->communicator(), psi_first_);
      Utilities::MPI::sum(second, distribution_->communicator(), psi_second_);
    }


    template <int dim>
    qp::Problem<typename DualProblem<dim>::VectorType>
    DualProblem<dim>::make_problem() const
    {
      qp::Problem<VectorType> problem;
      problem.hessian = [this](VectorType &dst, const VectorType &src)
      { apply_F(dst, src); };
      problem.b = d_;
      scaling_->transform(problem);
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
        auto equality = equalities_->constraints(n_multipliers());
        equality->projector_penalty_factor = projector_penalty_factor();
        problem.equality                   = equality;
        problem.semidefinite               = true;
      }
      return problem;
    }


    template <int dim>
    qp::Problem<typename DualProblem<dim>::DistributedVector>
    DualProblem<dim>::make_distributed_problem() const
    {
      AssertThrow(is_distributed(),
                  ExcMessage("DualProblem: a distributed QP asked for a "
                             "replicated dual problem."));
      using V = DistributedVector;
      qp::Problem<V> problem;
      problem.hessian = [this](V &dst, const V &src) { apply_F(dst, src); };
      problem.b       = *d_distributed_;
      scaling_->transform(problem);
      problem.hessian_storage = qp::HessianStorage::dense_matrix;

      // the blocks of the owned nodes only (the same as make_problem()'s)
      auto             set = std::make_shared<qp::SeparableSet<V>>();
      std::vector<int> owned_index(n_multipliers(), -1);
      for (const unsigned int r : distribution_->owned_rows())
        owned_index[r] = r;
      this->add_contact_blocks(*set, owned_index);
      set->finalize(problem.b);
      problem.constraints = set;

      if (!G_rows_.empty())
      {
        auto equality =
          equalities_->distributed_constraints(*distribution_, n_multipliers());
        equality->projector_penalty_factor = projector_penalty_factor();
        problem.equality                   = equality;
        problem.semidefinite               = true;
      }
      return problem;
    }


    template <int dim>
    void
    DualProblem<dim>::apply_F(DistributedVector       &dst,
                              const DistributedVector &src) const
    {
      Assert(is_distributed(), ExcInternalError());
      if (dst.size() != n_multipliers())
        initialize_multipliers(dst);
      operator_->vmult(dst, src, *distribution_);
    }


    template <int dim>
    double
    DualProblem<dim>::stiffness_setup_time() const
    {
      return inverse_.setup_time();
    }


    template <int dim>
    double
    DualProblem<dim>::stiffness_solve_time() const
    {
      return inverse_.solve_time();
    }


    template <int dim>
    bool
    DualProblem<dim>::is_assembled() const
    {
      return operator_->is_assembled();
    }


    template <int dim>
    const std::string &
    DualProblem<dim>::operator_description() const
    {
      return operator_->description();
    }


    template <int dim>
    double
    DualProblem<dim>::assembly_time() const
    {
      return operator_->assembly_time();
    }


    template <int dim>
    void
    DualProblem<dim>::apply_F(VectorType &dst, const VectorType &src) const
    {
      operator_->vmult(dst, src);
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
      if (is_distributed())
      {
        const std::vector<unsigned int> &owned_rows =
          distribution_->owned_rows();
        DistributedVector owned;
        initialize_multipliers(owned);
        for (unsigned int k = 0; k < owned_rows.size(); ++k)
          owned.begin()[k] = lambda(owned_rows[k]);
        return recover(owned, displacements, require_determined);
      }
      Vector<double> u;
      rows_.Tvmult(u, lambda);
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
      Assert(is_distributed(), ExcInternalError());
      Vector<double> u;
      rows_.Tvmult_owned(u,
                         lambda,
                         distribution_->owned_rows(),
                         distribution_->communicator());
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
      inverse_.apply(u);
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
      const std::vector<unsigned int> &owned_rows = distribution_->owned_rows();
      const std::vector<unsigned int> &owned_frictional =
        distribution_->owned_frictional();
      const MPI_Comm     communicator = distribution_->communicator();
      const unsigned int n_owned      = distribution_->owned_nodes().size();
      double             scale        = 0;
      for (unsigned int q = 0; q < n_owned; ++q)
        scale = std::max(scale, std::abs(lambda[q]));
      scale                 = Utilities::MPI::max(scale, communicator);
      const double      tol = 1e-8 * scale;
      std::vector<bool> active(owned_rows.size(), false);
      for (unsigned int q = 0; q < n_owned; ++q)
        active[q] = lambda[q] > tol;
      for (unsigned int p = 0; p < owned_frictional.size(); ++p)
      {
        const unsigned int j     = owned_frictional[p];
        const unsigned int first = n_owned + (dim - 1) * p;
        if (std::max(psi_first_[j], psi_second_[j]) > 0 &&
            friction_utilization(j, lambda + first) < 1 - 1e-6)
          for (unsigned int k = 0; k + 1 < dim; ++k)
            active[first + k] = true;
      }
      const bool determined = rigid_body_fit_.add(
        u, owned_rows, active, communicator, require_determined);
      split_displacements(u, displacements);
      return determined;
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
      return scaling_->scale();
    }


    template <int dim>
    unsigned long
    DualProblem<dim>::n_stiffness_solves() const
    {
      return inverse_.n_solves();
    }


    template class DualProblem<2>;
    template class DualProblem<3>;
  } // namespace contact
} // namespace dualcontact
