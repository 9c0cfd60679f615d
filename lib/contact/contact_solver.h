#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/vector.h>

#include <contact/coulomb_fixed_point.h>
#include <contact/dual_formulation.h>
#include <contact/working_set.h>
#include <qp/smalse_m.h>
#include <qp/solver_parameters.h>
#include <qp/solver_statistics.h>

#include <functional>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * What is appended to a run's reason when the recovery cannot fix the
     * rigid-body motion of a floating body (DualFormulation::recover
     * returned false): " (the multipliers leave ... set to zero)".
     */
    std::string
    undetermined_rigid_body_motion();


    /**
     * Solves the contact problem of a DualFormulation (DualProblem or
     * decomposition::TFETIDual): one QP for frictionless and Tresca scenes; for
     * Coulomb pairs the fixed point over Tresca problems psi_i = mu lambda_N,i
     * (the first one bonded: no bound on lambda_T, which is feasible for any
     * load), each QP warm started from the previous multipliers.  QPs with
     * equality constraints (floating bodies) go through SMALSE-M with the
     * chosen solver inside.
     *
     * The QPs run on the dual's vectors: dealii::Vector<double>
     * (replicated), or dealii::TrilinosWrappers::MPI::Vector with each
     * contact node's multipliers on one process (DualFormulation::
     * is_distributed()); then the Coulomb bounds and the recovery are
     * computed from the owned multipliers too, and Result::lambda is the
     * gathered whole vector (for the output).
     */
    template <int dim>
    class ContactSolver
    {
    public:
      struct Result
      {
        dealii::Vector<double>              lambda;
        std::vector<dealii::Vector<double>> displacements;
        /** One record per QP solved (Coulomb: per fixed-point iterate). */
        std::vector<qp::SolverStatistics> qp_statistics;
        /** Relative change of psi per Coulomb iterate. */
        std::vector<double> coulomb_changes;
        bool                converged = false;
        /** "converged", or why not (QP failure, Coulomb limit/divergence). */
        std::string reason;
        /**
         * The vector type the QPs ran on: "dealii::Vector<double>" or
         * "dealii::TrilinosWrappers::MPI::Vector".
         */
        std::string qp_vectors;
        /**
         * The multipliers each process held in the QP's vector (its locally
         * owned size, gathered; one entry when replicated).
         */
        std::vector<unsigned int> multipliers_per_process;
        /** What the working set did, one record per QP (as qp_statistics). */
        std::vector<WorkingSetRecord> working_sets;
      };

      ContactSolver(DualFormulation<dim>        &dual,
                    const qp::SolverParameters  &qp_parameters,
                    const qp::SMALSEMParameters &smalse_parameters,
                    const CoulombParameters     &coulomb_parameters,
                    const WorkingSetParameters  &working_set_parameters =
                      WorkingSetParameters());

      /** Solve; @p on_iterate (if set) sees every Coulomb iterate. */
      Result
      solve(const std::function<void(const Result &)> &on_iterate = {});

      /**
       * A progress hook: called after every Coulomb iterate's change of the
       * slip bounds is known (result.coulomb_changes.back(), the QP of the
       * iterate result.qp_statistics.back()), before anything else is done
       * with it (unlike solve()'s @p on_iterate, which gets the recovered
       * displacements and costs a stiffness solve per body).
       */
      void
      set_coulomb_monitor(std::function<void(const Result &)> monitor);

      /**
       * Whether solve() ends with the recovery of Result::displacements
       * (default true).  A caller that recovers the displacements itself
       * (ContactStage, in its own Recovery phase) switches it off, so that
       * the stiffness solves of the recovery run once; Result::displacements
       * then stays empty (the Coulomb iterates given to solve()'s
       * on_iterate are recovered all the same).
       */
      void
      set_final_recovery(bool recover);

      /**
       * Start the first QP from @p lambda (all multipliers, the whole
       * vector; empty: from zero): a load step warm-started from the
       * previous step's multipliers.  The first Coulomb iterate stays
       * bonded (the previous step's bounds may not carry the new load).
       */
      void
      set_initial_multipliers(const dealii::Vector<double> &lambda);

    private:
      /** solve() on the vectors @p V of the QP. */
      template <typename V>
      Result
      solve_on(const std::function<void(const Result &)> &on_iterate);

      /**
       * One QP from the dual's current slip bounds, warm started; on
       * replicated vectors through the WorkingSet (recorded in @p record).
       */
      template <typename V>
      qp::SolverStatistics
      solve_qp(V &lambda, WorkingSetRecord &record) const;

      /**
       * The chosen solver (or the chain auto) on @p problem, to
       * @p tolerance if positive (else the QP solver's own).
       */
      template <typename V>
      qp::SolverStatistics
      run_solver(const qp::Problem<V> &problem,
                 V                    &lambda,
                 const double          tolerance = 0.) const;

      /** The outer working-set loop (see WorkingSet). */
      qp::SolverStatistics
      solve_on_working_set(dealii::Vector<double> &lambda,
                           WorkingSetRecord       &record) const;

      DualFormulation<dim>               &dual_;
      qp::SolverParameters                qp_parameters_;
      qp::SMALSEMParameters               smalse_parameters_;
      CoulombParameters                   coulomb_parameters_;
      WorkingSetParameters                working_set_parameters_;
      std::function<void(const Result &)> coulomb_monitor_;
      bool                                final_recovery_ = true;
      dealii::Vector<double>              initial_multipliers_;
    };
  } // namespace contact
} // namespace dualcontact
