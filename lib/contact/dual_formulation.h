#pragma once

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <contact/contact_discretization.h>
#include <qp/problem.h>
#include <qp/separable_set.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * The dual of the contact problem of a scene as ContactSolver and the
     * driver use it, whatever its primal side:
     *
     *   minimize 1/2 lambda'F lambda - lambda'd
     *   subject to lambda_N >= 0, lambda_T,i in the friction set of node i,
     *              further multipliers free, G lambda = e,
     *
     * F = B K^# B', d = B K^# f - c, G = R'B', e = R'f.  Two
     * implementations:
     *  - DualProblem: the undecomposed dual, K block diagonal over the
     *    bodies with the Dirichlet conditions built in, B the contact rows
     *    only (all multipliers are contact multipliers);
     *  - decomposition::TFETIDual: total FETI, K block diagonal over the
     *    subdomains of every body, all floating, B the contact rows and the
     *    gluing and Dirichlet rows (free multipliers).
     *
     * <b>Layout.</b> Every implementation puts the contact multipliers
     * first, in the layout of DualProblem: [lambda_N (one per contact node);
     * lambda_T (dim - 1 per frictional node, in node order)], then whatever
     * else it has.  So the contact forces of lambda are read the same way
     * from every dual (the first n_contact_multipliers() entries), and the
     * friction sets, the slip bounds and the Coulomb fixed point (which only
     * concern the contact multipliers) are this class' own.
     *
     * <b>Slip bounds.</b> lambda are nodal forces [N, N/m in 2D]:
     * lambda_N,i = p_i w_i.  The nodal slip bound of a Tresca pair is
     * psi_i = g w_i, of a Coulomb pair psi_i = mu lambda_N,i; the friction
     * set of a node is a box [-psi, psi] in 2D, a disc (isotropic) or an
     * ellipse with semi-axes psi_1, psi_2 along t_1, t_2 (orthotropic) in
     * 3D.
     *
     * <b>Distribution.</b> A dual may run its QP on distributed vectors
     * (is_distributed()); the functions on DistributedVector are then
     * overridden.  A dual that runs on one process only keeps their
     * defaults, which throw.
     */
    template <int dim>
    class DualFormulation
    {
    public:
      using VectorType        = dealii::Vector<double>;
      using DistributedVector = dealii::TrilinosWrappers::MPI::Vector;

      explicit DualFormulation(const ContactDiscretization<dim> &contact);
      virtual ~DualFormulation() = default;

      /** @name The multipliers */
      /** @{ */
      /** All multipliers (contact ones first, see "Layout"). */
      virtual unsigned int
      n_multipliers() const = 0;
      /** The contact multipliers: normal and tangential. */
      unsigned int
      n_contact_multipliers() const;
      unsigned int
      n_contact_nodes() const;
      /** Nodes with tangential multipliers (frictional pairs). */
      unsigned int
      n_frictional_nodes() const;
      /** Index into the frictional nodes, or -1 for a frictionless node. */
      int
      frictional_index(const unsigned int node) const;
      /** Number of rigid-body modes of the primal side (rows of G). */
      virtual unsigned int
      n_rigid_body_modes() const = 0;
      /** The contact rows (nodes, gaps, B_N, B_T) the dual is built on. */
      const ContactDiscretization<dim> &
      contact() const;
      /** @} */

      /** @name Slip bounds (see the class documentation) */
      /** @{ */
      /** Whether some pair has Coulomb friction (bounds depend on lambda). */
      bool
      has_coulomb_friction() const;
      /**
       * Nodal slip bounds [N] of the frictional nodes (size
       * n_frictional_nodes(); @p second is used by orthotropic pairs in 3D
       * only).
       */
      void
      set_slip_bounds(const std::vector<double> &first,
                      const std::vector<double> &second);
      /**
       * The bounds of the pairs' laws: Tresca psi = g w_i; Coulomb
       * psi = mu lambda_N,i with lambda_N from @p lambda, or, if @p lambda is
       * null, no bound at all (bonded: the first Coulomb iterate, feasible
       * for any load).
       */
      void
      update_slip_bounds(const VectorType *lambda);
      const std::vector<double> &
      slip_bounds_first() const;
      const std::vector<double> &
      slip_bounds_second() const;
      /**
       * How much of its friction bound the tangential multiplier of the
       * @p j-th frictional node uses: |lambda_T| / psi in 2D and for
       * isotropic laws, sqrt((lambda_1/psi_1)^2 + (lambda_2/psi_2)^2) for
       * orthotropic ones.  Below 1: the node sticks; 1: it may slip.
       */
      double
      friction_utilization(const VectorType  &lambda,
                           const unsigned int j) const;
      /** @} */

      /**
       * The QP with the current slip bounds, scaled: Hessian F / s and
       * right-hand side d / s with s = scale(), the rows of G orthonormal.
       * The minimizer is that of the unscaled problem.
       */
      virtual qp::Problem<VectorType>
      make_problem() const = 0;

      /**
       * The load of a new load step (driver::LoadSteps): the bodies' loads
       * and the contact's offsets as they are now, and the slip
       * @p previous_slip = B_T u of the previous step (dim - 1 values per
       * contact node; empty: none), on which friction acts from now on
       * (design.md, "Load history").  F stays.  The default throws: a dual
       * without load steps.
       */
      virtual void
      update_load(const VectorType &previous_slip);

      /**
       * The displacements of every body (each with its constraints
       * distributed) for multipliers @p lambda.  When no active constraint
       * determines a rigid-body motion: with @p require_determined this
       * throws, otherwise the motion is left at zero and false is returned.
       */
      virtual bool
      recover(const VectorType                    &lambda,
              std::vector<dealii::Vector<double>> &displacements,
              const bool require_determined = true) const = 0;

      /** @name Distributed QP vectors (defaults: one process only) */
      /** @{ */
      virtual bool
      is_distributed() const;
      /** Owned contact nodes per process (one entry on one process). */
      virtual const std::vector<unsigned int> &
      contact_nodes_per_process() const = 0;
      virtual void
      initialize_multipliers(DistributedVector &lambda) const;
      virtual void
      gather(const DistributedVector &lambda, VectorType &whole) const;
      virtual qp::Problem<DistributedVector>
      make_distributed_problem() const;
      virtual void
      update_slip_bounds(const DistributedVector &lambda);
      virtual bool
      recover(const DistributedVector             &lambda,
              std::vector<dealii::Vector<double>> &displacements,
              const bool require_determined = true) const;
      /** @} */

      /** @name Figures for the log and the statistics */
      /** @{ */
      /** s = lambda_max(F) (power iteration) [m/N]. */
      virtual double
      scale() const = 0;
      /** One line on how F is applied (and why). */
      virtual const std::string &
      operator_description() const = 0;
      /** Number of K^# applications so far. */
      virtual unsigned long
      n_stiffness_solves() const = 0;
      /** Wall time [s] of the factorizations. */
      virtual double
      stiffness_setup_time() const = 0;
      /** Wall time [s] of all K^# solves so far. */
      virtual double
      stiffness_solve_time() const = 0;
      /** Wall time [s] of assembling F (0 if implicit). */
      virtual double
      assembly_time() const = 0;
      /** @} */

    protected:
      /**
       * Adds the friction set of every frictional node with a finite bound
       * to @p set (and the bound lambda_N >= 0 of every node), in the
       * layout above; bonded nodes (infinite bounds) stay free.
       */
      void
      add_contact_blocks(qp::SeparableSet<VectorType> &set) const;

    public:
      /**
       * The friction sets of add_contact_blocks() for a QP on some of the
       * multipliers only (contact::WorkingSet): multiplier r is at
       * @p new_index[r] of the smaller QP, or dropped (fixed at zero) when
       * that is negative.  A node's tangential block is kept or dropped
       * whole (the first of its rows decides).  On DistributedVector:
       * the blocks of a process' own multipliers (DualProblem).
       */
      template <typename V>
      void
      add_contact_blocks(qp::SeparableSet<V>    &set,
                         const std::vector<int> &new_index) const;

    protected:
      /** friction_utilization() from the node's dim - 1 tangential values. */
      double
      friction_utilization(const unsigned int j,
                           const double      *tangential) const;

      /**
       * Whether contact row @p r (of the first n_contact_multipliers())
       * must hold with equality at @p lambda: a normal row with a positive
       * multiplier (above @p tolerance), a tangential row of a sticking
       * node (multiplier strictly inside a nonzero friction set).
       */
      bool
      contact_row_is_active(const VectorType  &lambda,
                            const unsigned int r,
                            const double       tolerance) const;

      const ContactDiscretization<dim> &contact_;
      std::vector<int>                  frictional_index_;
      std::vector<unsigned int>         frictional_nodes_;
      std::vector<double>               psi_first_, psi_second_;
    };
  } // namespace contact
} // namespace dualcontact
