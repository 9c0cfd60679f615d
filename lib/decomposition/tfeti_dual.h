#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <contact/contact_discretization.h>
#include <contact/dual_formulation.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <decomposition/coarse_problem.h>
#include <decomposition/constraint_rows.h>
#include <decomposition/decomposition_parameters.h>
#include <decomposition/distributed_mesh.h>
#include <decomposition/dual_preconditioner.h>
#include <decomposition/multiplier_ownership.h>
#include <decomposition/subdomain.h>

#include <fem/elastic_body.h>
#include <fem/stiffness_solver.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * The TFETI (total FETI) dual of a contact scene: every body is cut
     * into subdomains (partition_cells()), each with its own copy of its
     * dofs (Subdomain), and
     *
     *   K = diag(K_s), f = [f_s], R = diag(R_s),
     *   B = [B_contact; B_gluing; B_dirichlet],
     *   F = sum_s B_s K_s^+ B_s',  d = B K^+ f - c,  G = R'B',  e = R'f,
     *
     *   minimize 1/2 lambda'F lambda - lambda'd
     *   subject to lambda_N >= 0, lambda_T,i in the friction set of node i,
     *              G lambda = e,
     *
     * the gluing and Dirichlet multipliers free.  Every subdomain floats
     * (K_s has the dim (dim + 1) / 2 rigid-body motions as kernel; K_s^+
     * is its pseudoinverse, Subdomain::apply_pseudoinverse()), so G has
     * that many rows per subdomain: the coarse problem.
     *
     * <b>Rows of B</b> (the multipliers in this order):
     *  - contact rows: the rows of contact::ContactDiscretization (B_N, and
     *    B_T of the frictional nodes), each body dof mapped to its copy in
     *    the lowest-numbered subdomain that has it; c = [gap - B_N u_D;
     *    -B_T u_D] as in the undecomposed dual (the contact matrices have
     *    the Dirichlet dofs condensed out);
     *  - gluing rows, non-redundant: a dof shared by the subdomains
     *    s_1 < ... < s_k (not under a Dirichlet condition) gets k - 1 rows,
     *    by default the chain u_{s_j} - u_{s_j+1} = 0 (entries +1, -1),
     *    else Helmert's orthonormal rows (DecompositionParameters::Gluing);
     *  - Dirichlet rows: every copy of a dof under a Dirichlet condition
     *    gets its own row u_s = u_D (entry 1; c = u_D), and no gluing row
     *    (it would repeat the difference of two Dirichlet rows).
     * B has full row rank wherever the undecomposed contact rows have.
     *
     * <b>The QP</b> has the contact multipliers first, in the layout of
     * contact::DualFormulation, so the contact forces, friction sets, slip
     * bounds and the Coulomb loop are those of the undecomposed dual.  It is
     * scaled as the undecomposed one, Hessian F / s and d / s, but with
     * s = lambda_max(P F P) (Lanczos; estimate_scale()), the operator
     * SMALSE-M's coarse projector iterates with, and G with orthonormal
     * rows: G~ =
     * L^{-1} P G, e~ = L^{-1} P e with P G G' P' = L L' (CoarseProblem:
     * G G' is sparse, factorized once by CHOLMOD; a singular G G' is a
     * rigid-body motion nothing holds).
     *
     * <b>F</b> is applied by local solves: B_s' lambda, K_s^+ (two
     * triangular solves with the subdomain's factor, and the removal of
     * the kernel before and after), B_s.
     *
     * <b>Preconditioner</b> (DualPreconditioner).  The problem supplies the
     * lumped preconditioner s Q B K B' Q or, when built, the Dirichlet one s Q
     * B S B' Q (S = diag(S_s), the subdomains' interface Schur complements), as
     * its free-set preconditioner, with the scaling Q = (B B')^{-1} (Rixen
     * and Farhat 1999): for the non-redundant gluing rows, B K B' alone
     * misses F^{-1} by the square of the chain's matrix at a dof shared by
     * k subdomains (condition number 34 at k = 4, 640 at k = 8), and
     * measured it cost iterations; Q makes the two exact at such a dof
     * (Q B S B' Q = F^{-1} for one dof with equal stiffnesses).  B B' is
     * sparse (rows meet only at shared dofs) and factorized once.  Used: MPRGP,
     * MPGP and MPGP-BB use it in face with `Preconditioner = lumped' or
     * `dirichlet' (SMALSE-M composes it with the coarse projector: P M P +
     * G~'G~ / rho).
     *
     * <b>Recovery</b>: u_s = K_s^+(f_s - B_s'lambda) + R_s alpha_s, alpha
     * the least-squares solution of G_A' alpha = -(B u - c)_A over the rows
     * A that must hold with equality (gluing, Dirichlet, active contact
     * rows).  The field of a body takes every dof from its first copy;
     * max_interface_jump() is the largest difference between two copies
     * of a dof (the gluing residual).
     *
     * <b>Processes.</b> Under MPI every process owns whole subdomains
     * (balanced by their dofs, largest first onto the least loaded
     * process) and assembles, factorizes and solves only these; no process
     * holds a global stiffness matrix or all of B.  The coarse problem is
     * replicated: every process keeps G (gathered once from the processes'
     * R_s'B_s') and the sparse Cholesky factor of G G'.
     *
     * <b>Distributed multipliers</b> (DecompositionParameters::
     * distributed_multipliers, the default on more than one process): a
     * row of B belongs to the process of one subdomain it touches (of
     * the lowest on even rows, of the highest on odd ones, so that a chain
     * of gluing rows alternates; all rows of a contact node to the lowest
     * subdomain over the node's rows), and the QP
     * runs on dealii::TrilinosWrappers::MPI::Vector with these owners.  F
     * lambda reads the rows its subdomains touch from their owners and adds
     * B_s u_s into them (MultiplierExchange: messages between the
     * processes that share rows, of the shared rows only); G~ lambda is a
     * sum of n_modes() numbers over the processes, G~'y the owned columns
     * of G.  The preconditioners, the recovery and the Coulomb bounds
     * gather the whole vector (once per application; the preconditioners'
     * scaling (B B')^{-1} is one replicated factor).
     *
     * <b>Replicated multipliers</b> (one process, or `QP vectors =
     * replicated'): every process keeps lambda, d and c, and F lambda is
     * the sum over the owned subdomains followed by one MPI_Allreduce of the
     * multiplier vector; the QP runs on dealii::Vector on every process in
     * lockstep (the reductions give every process the same bits).  Either
     * way the result does not depend on the number of processes beyond
     * round-off.  The recovered field
     * is assembled from the owned subdomains and summed over the processes:
     * every process gets the whole field of every body, and each process
     * writes its cells.
     *
     * <b>Meshes.</b> Replicated (parallel::shared: every process holds
     * every cell and takes its subdomains' cells), or distributed
     * (DistributedMesh: each process holds its subdomains' cells and a
     * layer of ghosts; the cut and the owners are DistributedMesh's, the
     * dof lists of the other processes' subdomains are gathered).
     *
     * Hanging nodes (local and contact refinement) are multiplier rows
     * u_h - sum_j w_j u_j = 0, counted with the gluing rows.
     */
    template <int dim>
    class TFETIDual : public contact::DualFormulation<dim>
    {
    public:
      using VectorType        = dealii::Vector<double>;
      using DistributedVector = dealii::TrilinosWrappers::MPI::Vector;
      using contact::DualFormulation<dim>::recover;
      using contact::DualFormulation<dim>::update_slip_bounds;

      /**
       * Cuts the bodies (counts from @p parameters), assembles and
       * factorizes the subdomains this process owns (of the processes of
       * @p communicator) with solvers made by @p make_solver (serial ones:
       * each factor stays on its process), builds B, d, G, e and the
       * coarse problem.  Collective.  With @p distributed_mesh the bodies'
       * meshes are its distributed ones: the cut and the owners are its,
       * and each process knows the cells of its own subdomains only.
       */
      TFETIDual(const std::vector<const fem::ElasticBody<dim> *> &bodies,
                const contact::ContactDiscretization<dim>        &contact,
                const DecompositionParameters                    &parameters,
                const std::function<std::unique_ptr<fem::StiffnessSolver>()>
                                           &make_solver,
                MPI_Comm                    communicator     = MPI_COMM_WORLD,
                const DistributedMesh<dim> *distributed_mesh = nullptr);

      unsigned int
      n_multipliers() const override;
      unsigned int
      n_rigid_body_modes() const override;
      qp::Problem<VectorType>
      make_problem() const override;
      bool
      recover(const VectorType                    &lambda,
              std::vector<dealii::Vector<double>> &displacements,
              const bool require_determined = true) const override;
      const std::vector<unsigned int> &
      contact_nodes_per_process() const override;
      /**
       * The load of a new load step (driver::LoadSteps), once the bodies'
       * loads are at its time and the contact's offsets updated
       * (contact::ContactDiscretization::update_offsets()): every owned
       * subdomain's f_s re-assembled (Subdomain::assemble_load()), the rows'
       * c from the new gaps, offsets and prescribed values
       * (ConstraintRows::update_rhs()), and with the previous step's slip
       * s = B_T u^(k-1) + o_T(k-1) (all nodes, dim - 1 per node; empty:
       * zero) on the tangential rows, so that friction acts on the slip
       * increment: d = B K^+ f - [c_N; c_T + s; c_rest], e = R'f and
       * e~ = L^{-1} P e again.  F, the subdomains' factorizations, the
       * coarse factor, the preconditioner and the scale stay.  Collective.
       */
      void
      update_load(const VectorType &previous_slip) override;

      /** @name Distributed multipliers (see "Processes") */
      /** @{ */
      bool
      is_distributed() const override;
      void
      initialize_multipliers(DistributedVector &lambda) const override;
      void
      gather(const DistributedVector &lambda, VectorType &whole) const override;
      qp::Problem<DistributedVector>
      make_distributed_problem() const override;
      void
      update_slip_bounds(const DistributedVector &lambda) override;
      bool
      recover(const DistributedVector             &lambda,
              std::vector<dealii::Vector<double>> &displacements,
              const bool require_determined = true) const override;
      /** dst = F src on distributed multipliers (collective). */
      void
      apply_F(DistributedVector &dst, const DistributedVector &src) const;
      /** @} */

      double
      scale() const override;
      const std::string &
      operator_description() const override;
      unsigned long
      n_stiffness_solves() const override;
      double
      stiffness_setup_time() const override;
      double
      stiffness_solve_time() const override;
      double
      assembly_time() const override;

      /** dst = F src (collective). */
      void
      apply_F(VectorType &dst, const VectorType &src) const;

      /** Whether the QP gets the Dirichlet preconditioner (else the
       *  lumped one, or none: DecompositionParameters::preconditioner). */
      bool
      has_dirichlet_preconditioner() const;
      /** Wall time [s] of building the preconditioner: B B' and its
       *  factor, and the interior factorizations of the Dirichlet one (the
       *  slowest process; 0 without a preconditioner). */
      double
      preconditioner_setup_time() const;
      const VectorType &
      d() const;

      /** @name The decomposition */
      /** @{ */
      unsigned int
      n_subdomains() const;
      /** Whether this process owns subdomain @p s. */
      bool
      is_owned(const unsigned int s) const;
      /** Subdomain @p s, which this process must own. */
      const Subdomain<dim> &
      subdomain(const unsigned int s) const;
      /** The body dofs of subdomain @p s (sorted; on every process). */
      const std::vector<dealii::types::global_dof_index> &
      subdomain_dofs(const unsigned int s) const;
      /** Number of subdomains each process owns. */
      std::vector<unsigned int>
      subdomains_per_process() const;
      /** Subdomain dofs (copies counted) each process owns. */
      std::vector<unsigned int>
      subdomain_dofs_per_process() const;
      /** Subdomains of body @p b. */
      unsigned int
      n_subdomains_of_body(const unsigned int b) const;
      /** Primal unknowns: the dofs of all subdomains (copies counted). */
      unsigned int
      n_primal_dofs() const;
      unsigned int
      n_gluing_multipliers() const;
      unsigned int
      n_dirichlet_multipliers() const;
      /** Wall time [s] of partitioning and assembling the subdomains
       *  (the slowest process). */
      double
      decomposition_time() const;
      /** G and the sparse factor of G G' (sizes, set-up time). */
      const CoarseProblem &
      coarse_problem() const;
      /** The rows of B (entries of the owned subdomains only). */
      const ConstraintRows<dim> &
      constraint_rows() const;
      /**
       * Largest |u_s(i) - u_t(i)| over the copies of a dof at the last
       * recover() [m], and relative to the largest |u| there.
       */
      double
      max_interface_jump() const;
      double
      relative_interface_jump() const;
      /** @} */

    private:
      using contact::DualFormulation<dim>::contact_;
      using contact::DualFormulation<dim>::frictional_nodes_;

      using Entry = typename ConstraintRows<dim>::Entry;

      /**
       * partition_cells() (the first process' partition, broadcast), the dofs
       * of every subdomain, the owner of each, and the Subdomain objects of the
       * owned ones.
       */
      void
      decompose(const DecompositionParameters &parameters);
      /**
       * The cells of every subdomain of body @p b on this process, given
       * the owned subdomains' names (appended to @p names) and bodies:
       * all of them on a replicated mesh (partition_cells()), those of the
       * owned subdomains on a distributed one.
       */
      void
      cut_body(
        const unsigned int             b,
        const DecompositionParameters &parameters,
        std::vector<std::vector<typename Subdomain<dim>::CellIterator>> &cells,
        std::vector<std::string>                                        &names,
        std::vector<unsigned int> &body_of);
      /** dofs_ of every subdomain on every process, from those of the
       *  owned ones (a distributed mesh; collective). */
      void
      gather_subdomain_dofs();
      /** Whether body @p b, on a distributed mesh, has a rigid-body motion
       *  its Dirichlet conditions do not hold (collective). */
      bool
      floats_on_distributed_mesh(const unsigned int b) const;
      /** The owner of every subdomain: largest first onto the process with
       *  the fewest dofs so far. */
      void
      assign_owners();
      /** The largest @p x over the processes. */
      double
      max_over_processes(const double x) const;
      /** v := the sum of v over the processes. */
      void
      sum_over_processes(VectorType &v) const;
      /**
       * dst = sum_s B_s A_s B_s' src (collective), A_s applied by
       * @p local(s, y, v): y = A_s v in the local numbering of subdomain s
       * (y comes sized and zeroed): the products of DualPreconditioner.
       */
      void
      apply_between_B(
        VectorType       &dst,
        const VectorType &src,
        const std::function<
          void(unsigned int, VectorType &, const VectorType &)> &local) const;
      /** G = R'B', e, and the coarse problem (sparse factor of G G'). */
      void
      build_coarse_problem();
      /** e = R'f from the owned subdomains' loads (summed over the
       *  processes) and e~ = L^{-1} P e. */
      void
      form_coarse_rhs();
      /** c_: the rows' right-hand sides, the previous slip added on the
       *  tangential rows. */
      void
      form_row_rhs();
      /** d = B K^+ f - c_ (one solve with every owned factor;
       *  collective). */
      void
      form_linear_term();
      /** The owned parts of d and e~ (distributed multipliers). */
      void
      distribute_linear_terms();
      /**
       * rho / lambda_max(P F P) of SMALSE-M's coarse projector when its
       * `Projector penalty factor' is automatic: 1 in 3D with a floating
       * body, 3 otherwise (measured).
       */
      double
      projector_penalty_factor() const;

      /** scale_ = lambda_max(P F P) and lambda_max_F_ by Lanczos
       *  (collective). */
      void
      estimate_scale();
      /** v := P v = v - G~'G~ v, the coarse projector (collective). */
      void
      project(VectorType &v) const;
      /**
       * Which process owns which multipliers (MultiplierOwnership), and
       * the distributed d and e~.
       * Collective.
       */
      void
      distribute_multipliers();
      /**
       * w_s = B_s' lambda for every owned subdomain, lambda(r) at
       * @p lambda[r], or with @p relevant at @p lambda[relevant[s][e]]
       * for the e-th entry of B_s (the exchange's relevant rows).
       */
      void
      apply_Bt(
        const double                                 *lambda,
        std::vector<VectorType>                      &w,
        const std::vector<std::vector<unsigned int>> *relevant = nullptr) const;
      /** lambda += B_s u_s over the owned subdomains (no reduction),
       *  indexed as apply_Bt(). */
      void
      add_B(
        const std::vector<VectorType>                &u,
        double                                       *lambda,
        const std::vector<std::vector<unsigned int>> *relevant = nullptr) const;
      /** u_s = K_s^+ w_s for every owned subdomain. */
      void
      apply_K_inverse(const std::vector<VectorType> &w,
                      std::vector<VectorType>       &u) const;

      MPI_Comm                                   communicator_;
      unsigned int                               n_processes_ = 1, rank_ = 0;
      std::vector<const fem::ElasticBody<dim> *> bodies_;
      /** The bodies' distributed meshes, or null (replicated meshes). */
      const DistributedMesh<dim> *distributed_mesh_ = nullptr;
      /** Per subdomain: the Subdomain if owned here, else null. */
      std::vector<std::unique_ptr<Subdomain<dim>>> subdomains_;
      /** Per subdomain (on every process): its body dofs and its owner. */
      std::vector<std::vector<dealii::types::global_dof_index>> dofs_;
      std::vector<unsigned int>                                 owner_;
      /** The owned subdomains, ascending. */
      std::vector<unsigned int> owned_;
      std::vector<unsigned int> first_subdomain_;
      /** The rows of B u = c (the entries of the owned B_s). */
      std::unique_ptr<ConstraintRows<dim>> rows_;
      /** Per body dof, its copy in the lowest subdomain (s, local). */
      std::vector<std::vector<std::pair<unsigned int, unsigned int>>>
        first_copy_;

      /** G (modes numbered subdomain by subdomain) and the sparse
       *  factor of G G'; e, and e~ = L^{-1} P e. */
      std::unique_ptr<CoarseProblem> coarse_;
      VectorType                     e_;
      VectorType                     e_orthonormal_;

      VectorType d_;
      /** The right-hand side of every row of B u = c, with the previous
       *  step's slip on the tangential rows (form_row_rhs()). */
      VectorType c_;
      /** The slip B_T u + o_T of the previous load step (empty: none). */
      VectorType previous_slip_;
      double     scale_ = 1;
      /** lambda_max(F) (the scale s = scale_ is lambda_max(P F P)). */
      double lambda_max_F_ = 1;
      /** Whether a body has rigid-body modes (projector_penalty_factor()). */
      bool has_floating_body_ = false;
      /** Products F x the estimates of both took. */
      unsigned int              scale_products_ = 0;
      std::string               operator_description_;
      std::vector<unsigned int> nodes_per_process_;

      /** Distributed multipliers: the owned rows, the exchange, and per
       *  owned subdomain and entry of B_s the entry's relevant row. */
      bool                                      distributed_ = false;
      std::unique_ptr<MultiplierOwnership<dim>> ownership_;
      dealii::IndexSet                          owned_modes_;
      std::unique_ptr<DistributedVector>        d_distributed_;
      std::unique_ptr<DistributedVector>        e_distributed_;
      mutable std::vector<double>               relevant_values_;

      double                          decomposition_time_ = 0, setup_time_ = 0;
      mutable double                  solve_time_         = 0;
      mutable unsigned long           n_stiffness_solves_ = 0;
      mutable double                  max_jump_ = 0, relative_jump_ = 0;
      mutable std::vector<VectorType> work_, work_x_;
      /** The lumped or Dirichlet preconditioner (none: null). */
      std::unique_ptr<DualPreconditioner<dim>> preconditioner_;
      double                                   preconditioner_setup_time_ = 0;
    };
  } // namespace decomposition
} // namespace dualcontact
