#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/vector.h>

#include <contact/contact_discretization.h>
#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <decomposition/decomposition_parameters.h>
#include <decomposition/method_choice.h>
#include <decomposition/subdomain_solver.h>
#include <decomposition/tfeti_dual.h>
#include <driver/output_parameters.h>
#include <driver/run_log.h>
#include <driver/scene.h>
#include <io/contact_surface_mesh.h>
#include <io/contact_surface_writer.h>
#include <primal/primal_parameters.h>
#include <qp/smalse_m.h>
#include <qp/solver_parameters.h>

#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace driver
  {
    /**
     * The contact part of a run, on the bodies of a Scene: contact search
     * (nodes, frames, gaps, B_N, B_T), the dual problem (factorizes every
     * K), the QP or the Coulomb fixed point over QPs, recovery of the
     * displacements, and what is derived from the multipliers: the
     * contact-surface data of every pair (io::ContactSurfaceNode) and the
     * per-pair sums and counts of results.txt (PairResults).
     *
     * Parameters: `QP solver', `QP solver/SMALSE-M', `Coulomb', `Dual
     * problem', `Decomposition' (which dual: contact::DualProblem, or
     * decomposition::TFETIDual), and in
     * `Output' the `Write Coulomb iterates' switch and the `Contact status
     * tolerance'.  Each phase method appends console lines to @p details.
     */
    template <int dim>
    class ContactStage
    {
    public:
      /** Per contact pair: the sums and counts of results.txt. */
      struct PairResults
      {
        unsigned int           n_nodes      = 0;
        unsigned int           n_separated  = 0;
        unsigned int           n_stick      = 0;
        unsigned int           n_slip       = 0;
        unsigned int           n_contact    = 0; ///< frictionless, touching
        double                 normal_force = 0;
        dealii::Tensor<1, dim> tangential_force;
        /** The force the slave exerts on the master (or obstacle), normal
         *  and tangential together [N, N/m in 2D]. */
        dealii::Tensor<1, dim> contact_force;
        double                 max_pressure = 0;
        double                 min_gap      = 0;
        double                 max_gap      = 0;
        double                 area         = 0;
        /**
         * Length (2D) [m] or area (3D) [m^2] of the contact zone, its edge
         * located below the node spacing (contact::ContactExtent).
         */
        double contact_measure = 0;
      };

      /** Contact surfaces of every pair (one vector of nodes per pair). */
      using Surfaces = std::vector<std::vector<io::ContactSurfaceNode<dim>>>;

      /**
       * Read the parameters; @p prm is kept to make the stiffness solvers
       * (subsection `Stiffness solver') in setup_dual_problem().
       */
      /**
       * The stage of @p scene; @p prm for the solver subsections (and the
       * stiffness solvers created while setting up the dual), @p output for
       * the contact status tolerance and the Coulomb iterates.
       */
      ContactStage(dealii::ParameterHandler &prm,
                   const OutputParameters   &output,
                   Scene<dim>               &scene);
      ~ContactStage();

      /** Contact search phase: nodes, frames, gaps, B_N, B_T. */
      void
      discretize(std::vector<std::string> &details);
      /** Factorization phase: the dual problem (factorizes every K). */
      void
      setup_dual_problem(std::vector<std::string> &details);
      /**
       * A new load step (driver::LoadSteps), once the scene's loads are at
       * its time (Scene::set_load_time(), Scene::assemble_loads()): the
       * contact offsets of the new prescribed values, the dual's linear
       * term with friction on the slip increment since the last recover(),
       * and the next solve() warm-started from the last multipliers.  F and
       * the factorizations stay.
       */
      void
      start_load_step();
      /** QP phase: the QP (or the Coulomb fixed point over QPs). */
      void
      solve(std::vector<std::string> &details);
      /**
       * Recovery phase: the displacements of the scene's bodies from the
       * multipliers (the only recovery of the final multipliers: solve()
       * switches the contact solver's off), the contact surfaces (values and
       * cells) and the pair results; @p details gets TFETI's interface jump
       * and a rigid-body motion the multipliers leave undetermined.
       */
      void
      recover(std::vector<std::string> &details);
      /**
       * Let go of everything computed on the scene's bodies (contact
       * discretization, dual problem with its factors, results), before the
       * scene drops them to refine its meshes (ContactRefinement); the next
       * discretize() starts afresh.
       */
      void
      reset();

      /**
       * Show progress through @p log (null: none): the factorizations'
       * monitors, the QP solvers' progress hook, the Coulomb iterates.
       */
      void
      set_run_log(RunLog *log)
      {
        run_log_ = log;
      }

      const qp::SolverParameters &
      qp_parameters() const
      {
        return qp_parameters_;
      }
      const typename contact::ContactSolver<dim>::Result &
      result() const
      {
        return result_;
      }
      /** The dual (undecomposed, or TFETI with `Decomposition/Method'). */
      const contact::DualFormulation<dim> &
      dual() const
      {
        return *dual_;
      }
      /** The TFETI dual if the scene was decomposed, else null. */
      const decomposition::TFETIDual<dim> *
      tfeti() const
      {
        return dynamic_cast<const decomposition::TFETIDual<dim> *>(dual_.get());
      }
      const contact::ContactDiscretization<dim> &
      discretization() const
      {
        return *contact_;
      }
      /** The primal method's statistics (JSON object), empty if it did
       *  not run. */
      const std::string &
      primal_json() const
      {
        return primal_json_;
      }
      /** Sum of the QP solves' wall times [s]. */
      double
      qp_wall_time() const
      {
        return qp_wall_time_;
      }
      const Surfaces &
      surfaces() const
      {
        return surfaces_;
      }
      /** Per Coulomb iterate (if written): the surfaces of every pair. */
      const std::vector<Surfaces> &
      coulomb_iterates() const
      {
        return coulomb_iterates_;
      }
      /**
       * Per pair: its slave faces as the cells of the contact-surface file,
       * over the nodes of surfaces() (with the process owning each face).
       */
      const std::vector<io::ContactSurfaceMesh<dim>> &
      surface_meshes() const
      {
        return surface_meshes_;
      }
      const std::vector<PairResults> &
      pair_results() const
      {
        return pair_results_;
      }
      /**
       * Per pair: the energy dissipated by friction [J, J/m in 2D] over the
       * load steps so far, sum over steps and nodes of lambda_T,i . (slip
       * increment)_i (recover()).
       */
      const std::vector<double> &
      dissipated_energy() const
      {
        return dissipated_energy_;
      }
      /**
       * Per body (after recover()): the nodal forces the contact exerts on
       * it, all its pairs as slave and as master (its dofs, unconstrained;
       * contact::ContactDiscretization::nodal_contact_forces()).
       */
      const std::vector<dealii::Vector<double>> &
      body_contact_forces() const
      {
        return body_contact_forces_;
      }

      /**
       * Whether `Decomposition/Method' resolves to tfeti for this scene
       * (the bodies set up): the dual is TFETI.
       */
      bool
      decomposed() const;
      /**
       * Whether the solve needs the bodies' assembled K and f: every path
       * but the TFETI dual (the primal method factorizes the bodies' K).
       */
      bool
      needs_global_systems() const;

    private:
      /**
       * Appends to the failure reason what makes a frictional scene
       * unsolvable, when contact::FrictionCapacity finds it (no static
       * equilibrium of a floating body).
       */
      void
      explain_failure();


      /** The console line on the subdomains and multipliers of TFETI. */
      void
      describe_decomposition(std::vector<std::string> &details) const;

      /**
       * The contact-surface data of every pair for multipliers @p lambda and
       * displacements @p displacements, with the dual's current slip bounds.
       */
      Surfaces
      contact_surfaces(
        const dealii::Vector<double>              &lambda,
        const std::vector<dealii::Vector<double>> &displacements) const;
      /** B_T u + o_T of @p displacements ((dim - 1) values per contact
       *  node): the relative tangential displacement. */
      dealii::Vector<double>
      tangential_displacement(
        const std::vector<dealii::Vector<double>> &displacements) const;
      /** body_contact_forces() and every pair's contact_force from the
       *  final multipliers (recover()). */
      void
      compute_contact_forces();

      dealii::ParameterHandler      &prm_;
      Scene<dim>                    &scene_;
      RunLog                        *run_log_ = nullptr;
      qp::SolverParameters           qp_parameters_;
      qp::SMALSEMParameters          smalse_parameters_;
      contact::CoulombParameters     coulomb_parameters_;
      contact::WorkingSetParameters  working_set_parameters_;
      contact::DualProblemParameters dual_parameters_;
      /** `Decomposition': the undecomposed dual or TFETI. */
      decomposition::DecompositionParameters decomposition_parameters_;
      /** Whether the stiffness solver spreads its factor over the
       *  processes (mumps, amg); else every process here holds a copy. */
      bool solver_spreads_factor_ = false;
      /** `Decomposition/Method = automatic': the choice on the current
       * meshes, made on the first decomposed() (reset() forgets it). */
      mutable std::unique_ptr<decomposition::MethodChoice<dim>> method_choice_;
      /** `Contact solver = primal': the report's Uzawa-CGC (lib/primal). */
      primal::PrimalParameters primal_parameters_;
      /** Its statistics (JSON object) when it ran. */
      std::string primal_json_;
      bool        write_coulomb_iterates_ = false;
      /** Relative tolerance of the separated / stick / slip status. */
      double status_tolerance_ = 1e-6;

      std::unique_ptr<contact::ContactDiscretization<dim>> contact_;
      std::unique_ptr<contact::DualFormulation<dim>>       dual_;
      typename contact::ContactSolver<dim>::Result         result_;
      double                                               qp_wall_time_ = 0;
      Surfaces                                             surfaces_;
      std::vector<io::ContactSurfaceMesh<dim>>             surface_meshes_;
      std::vector<Surfaces>                                coulomb_iterates_;
      std::vector<PairResults>                             pair_results_;
      std::vector<dealii::Vector<double>>                  body_contact_forces_;
      /** B_T u + o_T of the last recover() (empty before the first). */
      dealii::Vector<double> slip_;
      /** slip_ when the current load step started (empty: the first). */
      dealii::Vector<double> previous_slip_;
      /** The multipliers the next solve() starts from (empty: zero). */
      dealii::Vector<double> warm_start_;
      std::vector<double>    dissipated_energy_;
    };
  } // namespace driver
} // namespace dualcontact
