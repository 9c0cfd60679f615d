#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <contact/assembled_dual_operator.h>
#include <contact/contact_discretization.h>
#include <contact/contact_rows.h>
#include <contact/dual_formulation.h>
#include <contact/dual_operator.h>
#include <contact/dual_transforms.h>
#include <contact/multiplier_distribution.h>
#include <contact/rigid_body_fit.h>
#include <contact/stiffness_inverse.h>
#include <fem/elastic_body.h>
#include <fem/generalized_inverse.h>
#include <fem/rigid_body_modes.h>
#include <fem/stiffness_solver.h>
#include <qp/problem.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * How the dual operator F = B K^# B' is applied (subsection
     * `Dual problem`).
     */
    struct DualProblemParameters
    {
      enum class Operator
      {
        /** assembled when the stiffness solver offers a Schur factor and
         *  the dense data fit the memory limit, else implicit */
        automatic,
        /** a dense m x m matrix W'W, W = L^{-1} B_C' with L the Cholesky
         *  factor of the Schur complement of K on the contact dofs C */
        assembled,
        /** one K^# solve (a forward and a backward substitution with the
         *  whole factor) per product */
        implicit
      };
      Operator form = Operator::automatic;
      /** Limit [MB] for the dense matrices of the assembled form. */
      double memory_limit = 4096;

      /** The vectors the QP runs on (see DualProblem, "Distribution"). */
      enum class Vectors
      {
        /** distributed when MPI_COMM_WORLD has more than one process */
        automatic,
        /** dealii::Vector<double>, the whole QP on every process */
        replicated,
        /** dealii::TrilinosWrappers::MPI::Vector, the multipliers of
         *  each contact node on one process (also on one process) */
        distributed
      };
      Vectors vectors = Vectors::automatic;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };


    /**
     * The dual of the contact problem of a scene, for one set of slip bounds
     * (one Tresca problem; the Coulomb loop changes the bounds):
     *
     *   minimize 1/2 lambda'F lambda - lambda'd
     *   subject to lambda_N >= 0, lambda_T,i in the friction set of node i,
     *              G lambda = e   (only if some body has rigid-body modes)
     *
     * with B = [B_N; B_T] (tangential rows only for nodes of frictional
     * pairs), F = B K^# B', d = B K^# f - [c; -o_T], G = R'B', e = R'f.
     * K^# is K^{-1} for a supported body and the fixing-dof generalized
     * inverse for a body with rigid-body modes R; c = gap - B_N u_D and o_T =
     * B_T u_D carry prescribed displacements (ContactDiscretization).
     *
     * lambda are nodal forces [N, N/m in 2D]: lambda_N,i = p_i w_i with the
     * contact pressure p_i and the node's area weight w_i.  Hence the nodal
     * slip bound of a Tresca pair is psi_i = g w_i and of a Coulomb pair
     * psi_i = mu lambda_N,i.  The friction set of a node is a box
     * [-psi, psi] in 2D, a disc of radius psi (isotropic) or an ellipse with
     * semi-axes psi_1, psi_2 along the node's tangents t_1, t_2 (orthotropic)
     * in 3D.
     *
     * Layout of lambda: [lambda_N (one per contact node); lambda_T
     * (dim - 1 per frictional node, in node order)].
     *
     * <b>Distribution.</b> With more than one process (or `set QP vectors =
     * distributed') the QP runs on dealii::TrilinosWrappers::MPI::Vector:
     * every contact node, with its normal and tangential multipliers (one
     * block of the separable set and the node's Coulomb bound), belongs to
     * one process: the one owning the node's first slave dof (or, when the
     * bodies are not partitioned, an even split of the nodes in order).
     * The global layout above is kept; a process owns a non-contiguous set
     * of indices.  Everything the contact search produced (B, f, R, d, G)
     * stays replicated, as the mesh of a parallel::shared::Triangulation
     * is; what is distributed is the QP's work: its vectors, the
     * projections onto the friction sets, the products with G, and the
     * product with F, which gathers what it needs and returns the owned
     * entries:
     *  - implicit F: each process applies B' to its owned multipliers, the
     *    partial displacement loads are summed over the processes (one
     *    MPI_Allreduce of the n dofs), K^# is applied by the (distributed)
     *    stiffness solver, and each process applies its rows of B;
     *  - assembled F: the multipliers are gathered (one MPI_Allreduce of
     *    the m multipliers) and each process multiplies by its rows of F
     *    (m_p x m flops instead of m x m).
     * G and e have their (few) rows on process 0; G products reduce over
     * the processes.  The Coulomb bounds psi of owned nodes are summed over
     * the processes (each node counted once), so the fixed point's change
     * is the same on every process.  The recovery applies B' to the owned
     * multipliers and fits the rigid-body amplitudes from the owned rows
     * (reduced sums); the displacements come out whole on every process,
     * as the output needs them.
     */
    template <int dim>
    class DualProblem : public DualFormulation<dim>
    {
    public:
      using VectorType = dealii::Vector<double>;
      /** The QP's vectors under MPI (see "Distribution"). */
      using DistributedVector = dealii::TrilinosWrappers::MPI::Vector;
      using DualFormulation<dim>::n_contact_nodes;
      using DualFormulation<dim>::n_frictional_nodes;
      using DualFormulation<dim>::frictional_index;
      using DualFormulation<dim>::has_coulomb_friction;
      using DualFormulation<dim>::set_slip_bounds;
      using DualFormulation<dim>::update_slip_bounds;
      using DualFormulation<dim>::slip_bounds_first;
      using DualFormulation<dim>::slip_bounds_second;
      using DualFormulation<dim>::friction_utilization;

      /**
       * Factorizes every body's K with a solver made by @p make_solver
       * (wrapped in a generalized inverse where the body has rigid-body
       * modes) and builds d, G, e; in the assembled form also the dense F.
       */
      DualProblem(
        const std::vector<const fem::ElasticBody<dim> *> &bodies,
        const ContactDiscretization<dim>                 &contact,
        const std::function<std::unique_ptr<fem::StiffnessSolver>()>
                                    &make_solver,
        const DualProblemParameters &parameters = DualProblemParameters());

      ~DualProblem() override;

      unsigned int
      n_multipliers() const override;
      /** Total number of rigid-body modes (rows of G). */
      unsigned int
      n_rigid_body_modes() const override;

      /**
       * The load of a new load step: f and e from the bodies' load vectors
       * (re-assembled, fem::ElasticBody::assemble_load()), c and o_T from
       * the contact's offsets (ContactDiscretization::update_offsets()),
       * and the previous step's slip s = B_T u^(k-1) (all nodes, dim - 1
       * per node; empty: zero), so that friction acts on the slip
       * increment: d = B K^+ f - [c; s - o_T].  F and the factorizations
       * stay.
       */
      void
      update_load(const dealii::Vector<double> &previous_slip) override;

      /** The same as DualFormulation::update_slip_bounds() from
       *  distributed multipliers (collective). */
      void
      update_slip_bounds(const DistributedVector &lambda) override;

      /**
       * Whether the QP runs on DistributedVector (more than one process,
       * or `set QP vectors = distributed').
       */
      bool
      is_distributed() const override;
      /** The multipliers this process owns (all of them if replicated). */
      const dealii::IndexSet &
      locally_owned_multipliers() const;
      /** Owned contact nodes per process (one entry if replicated). */
      const std::vector<unsigned int> &
      contact_nodes_per_process() const override;
      /** Owned multipliers per process (one entry if replicated). */
      const std::vector<unsigned int> &
      multipliers_per_process() const;
      /** A distributed vector of multipliers, zero (collective). */
      void
      initialize_multipliers(DistributedVector &lambda) const override;
      /** The whole vector of multipliers on every process (collective). */
      void
      gather(const DistributedVector &lambda, VectorType &whole) const override;

      /**
       * The QP with the current slip bounds (F counted by the solver), in
       * scaled form: Hessian F / s and right-hand side d / s with s the
       * largest eigenvalue of F (so that the Hessian has norm 1 and the
       * right-hand side is a force, like the multipliers and the equality
       * residual), and the rows of G orthonormalized (G G' = I).  The
       * minimizer is that of the unscaled problem.
       */
      qp::Problem<VectorType>
      make_problem() const override;

      /**
       * The same QP on distributed vectors: each process adds the blocks
       * of its own contact nodes to the separable set; the Hessian product
       * and G are those of "Distribution" above.  Collective.
       */
      qp::Problem<DistributedVector>
      make_distributed_problem() const override;

      /** dst = F src. */
      void
      apply_F(VectorType &dst, const VectorType &src) const;

      /**
       * dst = F src on distributed multipliers (collective; see
       * "Distribution" for what it communicates).
       */
      void
      apply_F(DistributedVector &dst, const DistributedVector &src) const;

      const VectorType &
      d() const;

      /** s = lambda_max(F) (power iteration) [m/N]. */
      double
      scale() const override;

      /**
       * Displacements of every body for multipliers @p lambda:
       * u = K^#(f - B'lambda) + R alpha, alpha fitted so that the
       * constraints whose multipliers are active (lambda_N,i > 0, and
       * tangential rows of sticking nodes) hold with equality, then the
       * constraints of each body distributed.
       *
       * When no active constraint sees a rigid-body mode (e.g. lambda = 0
       * from a QP solver that did not converge) the amplitudes are not
       * determined: with @p require_determined this throws (a converged
       * solution of an ill-posed scene), otherwise they are left at zero
       * and false is returned, so that a failed solve is reported as such
       * with its output instead of ending in this error.
       */
      bool
      recover(const VectorType                    &lambda,
              std::vector<dealii::Vector<double>> &displacements,
              const bool require_determined = true) const override;

      /**
       * The same from distributed multipliers: B' applied to the owned
       * ones, the rigid-body amplitudes fitted from the owned rows (sums
       * reduced over the processes).  The displacements are whole on every
       * process.  Collective.  @p require_determined and the return value
       * as above.
       */
      bool
      recover(const DistributedVector             &lambda,
              std::vector<dealii::Vector<double>> &displacements,
              const bool require_determined = true) const override;

      /** Number of K^# applications so far (one per implicit F product). */
      unsigned long
      n_stiffness_solves() const override;

      /** Wall time [s] of the bodies' factorizations (with Schur factors). */
      double
      stiffness_setup_time() const override;

      /** Wall time [s] of all K^# solves so far (over all bodies). */
      double
      stiffness_solve_time() const override;

      /** Whether F is held as a dense matrix (see DualProblemParameters). */
      bool
      is_assembled() const;

      /**
       * One line on the form of F: "assembled (m x m; Schur complements of
       * sizes ...)" or "implicit (...)", with the reason for the choice.
       */
      const std::string &
      operator_description() const override;

      /** Wall time [s] of assembling F (Schur factors excluded). */
      double
      assembly_time() const override;

    private:
      using DualFormulation<dim>::contact_;
      using DualFormulation<dim>::frictional_index_;
      using DualFormulation<dim>::frictional_nodes_;
      using DualFormulation<dim>::psi_first_;
      using DualFormulation<dim>::psi_second_;

      /**
       * The two recover()s once u = B'lambda: u = K^+(f - u), plus the
       * rigid-body motion R alpha fitted so that the active rows hold, then
       * the bodies' parts.  @p lambda: the owned multipliers in the local
       * order of MultiplierDistribution::owned_rows() (replicated: all
       * rows); the sums over the owned rows are reduced over its
       * communicator (one process when replicated).  Collective when
       * distributed; @p require_determined and the return value as in
       * recover().
       */
      bool
      finish_recovery(const double                        *lambda,
                      dealii::Vector<double>              &u,
                      std::vector<dealii::Vector<double>> &displacements,
                      const bool require_determined) const;

      /** The bodies' parts of @p u, their constraints distributed. */
      void
      split_displacements(
        const dealii::Vector<double>        &u,
        std::vector<dealii::Vector<double>> &displacements) const;

      /** d from load_, the contact's offsets and previous_slip_. */
      void
      form_linear_term();

      /**
       * rho / lambda_max(P F P) of SMALSE-M's coarse projector when its
       * `Projector penalty factor' is automatic: 10 for bounds and boxes,
       * 1 for friction discs and ellipses (measured).
       */
      double
      projector_penalty_factor() const;

      /**
       * Turns the rows @p rows of body @p body in the assembled F, which
       * its Schur factor gives as B K^# B', into B K^+ B' (@p inverse:
       * the body's; lib/contact/README.md, "Pseudoinverses").  With W =
       * B K^# R, G = R'B' and C = R'K^#R on those rows, B K^+ B' =
       * B K^# B' - W G - G'W' + G'C G: one K^# solve per rigid-body mode.
       * The body's modes are G_rows_ from @p first_mode on.
       */
      void
      add_pseudoinverse_terms(const unsigned int               body,
                              const unsigned int               first_mode,
                              const fem::GeneralizedInverse   &inverse,
                              const std::vector<unsigned int> &rows,
                              AssembledDualOperator<dim>      &F) const;

      /** The owners of the multipliers (constructor, last). */
      void
      distribute_multipliers(const DualProblemParameters &parameters);

      std::vector<const fem::ElasticBody<dim> *>             bodies_;
      std::vector<std::unique_ptr<fem::RigidBodyModes<dim>>> modes_;
      /** B in the multipliers' layout. */
      ContactRows<dim> rows_;
      /** K^+ of the bodies (their factorized solvers; K^-1 where no
       *  rigid-body mode is free). */
      StiffnessInverse<dim> inverse_;
      /** F: assembled or implicit. */
      std::unique_ptr<DualOperator<dim>> operator_;
      /** Stacked load f and the columns of R over all dofs. */
      dealii::Vector<double>              load_;
      std::vector<dealii::Vector<double>> rigid_modes_;
      /** G as rows (each of size n_multipliers()) and e. */
      std::vector<VectorType> G_rows_;
      VectorType              e_;
      VectorType              d_;
      /** The slip B_T u of the previous load step (empty: none). */
      VectorType previous_slip_;
      /** The rigid-body amplitudes of the recovery. */
      RigidBodyFit<dim> rigid_body_fit_;
      /** The transforms of the QP: F / s, d / s, and G~, e~. */
      std::unique_ptr<LambdaMaxScaling>      scaling_;
      std::unique_ptr<OrthonormalEqualities> equalities_;

      /** Which process owns which multipliers (see "Distribution"). */
      std::unique_ptr<MultiplierDistribution> distribution_;
      /** Made only when distributed: the constructor of a Trilinos vector
       *  calls MPI, which serial programs do not initialize. */
      std::unique_ptr<DistributedVector> d_distributed_;
    };
  } // namespace contact
} // namespace dualcontact
