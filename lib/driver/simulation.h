#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <contact/contact_discretization.h>
#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <driver/body_parameters.h>
#include <driver/contact_pair_parameters.h>
#include <driver/obstacle_parameters.h>
#include <fem/elastic_body.h>
#include <fem/stiffness_solver.h>
#include <io/contact_surface_writer.h>
#include <io/output_folder.h>
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
     * One run of a scene of elastic bodies: meshes, setup, assembly, then
     * either one stiffness solve per body (no contact pairs) or the contact
     * problem (contact search, factorization of every K inside the dual
     * problem, the dual QP / Coulomb fixed point, recovery of the
     * displacements), derived results, output.
     *
     * Everything a user can get wrong is checked before anything is written:
     * the constructor parses and checks all parameters (including that the
     * output folder can be written and that files exist), run() builds and
     * checks the meshes (cells, boundary and material ids) before it
     * assembles.  The output folder receives its files only at the end,
     * under temporary names renamed when all are complete
     * (io::OutputFolder).
     *
     * Console output goes to @p console (rank 0 only under MPI); each
     * phase prints one progress line with its wall time.
     */
    template <int dim>
    class Simulation
    {
    public:
      Simulation(dealii::ParameterHandler   &prm,
                 const std::string          &parameter_file,
                 dealii::ConditionalOStream &console);
      ~Simulation();

      /**
       * Run the scene and write its output.  Returns false if the contact
       * solver did not converge: the output is written all the same
       * (flagged as not converged in results.txt and statistics.json), so
       * that a failed run can be inspected; the program then exits with 2.
       */
      bool
      run();

    private:
      /** Per body: what was computed from the solution. */
      struct BodyResults
      {
        double                 strain_energy    = 0;
        double                 external_work    = 0;
        double                 max_displacement = 0;
        dealii::Tensor<1, dim> applied_force;
        std::map<dealii::types::boundary_id, dealii::Tensor<1, dim>>
          reaction_forces;
      };

      void
      create_meshes();
      void
      setup();
      void
      assemble();
      void
      solve();
      /** Contact: search, nodes, frames, gaps, B_N, B_T. */
      void
      discretize_contact();
      /** Contact: the dual problem (factorizes every K). */
      void
      setup_dual_problem();
      /** Contact: the QP (or the Coulomb fixed point over QPs). */
      void
      solve_contact();
      /** Contact: displacements from the multipliers, contact results. */
      void
      recover();
      /**
       * The contact-surface data of every pair for multipliers @p lambda and
       * displacements @p displacements, with the dual's current slip bounds.
       */
      std::vector<std::vector<io::ContactSurfaceNode<dim>>>
      contact_surfaces(
        const dealii::Vector<double>              &lambda,
        const std::vector<dealii::Vector<double>> &displacements) const;
      void
      postprocess();
      /** The VTU/PVTU/PVD files (timed as the phase `Output'). */
      void
      write_output();
      /**
       * results.txt, statistics.json, used_parameters.prm, then rename all
       * files to their final names.
       */
      void
      write_records();

      std::string
      results_text() const;
      std::string
      statistics_json() const;

      /** Run @p phase timed, then print its line and @p details lines. */
      template <typename Phase>
      void
      run_phase(const std::string &name, const Phase &phase);

      dealii::ParameterHandler   &prm_;
      const std::string           parameter_file_;
      dealii::ConditionalOStream &console_;
      const bool                  is_output_rank_;
      dealii::TimerOutput         timer_;

      unsigned int                      fe_degree_ = 1;
      bool                              write_vtu_ = true;
      std::unique_ptr<io::OutputFolder> output_folder_;

      std::vector<BodyParameters<dim>>                         body_parameters_;
      std::vector<std::shared_ptr<dealii::Triangulation<dim>>> triangulations_;
      std::vector<std::unique_ptr<fem::ElasticBody<dim>>>      bodies_;
      std::vector<std::unique_ptr<fem::StiffnessSolver>>       solvers_;
      std::vector<dealii::Vector<double>>                      displacements_;
      std::vector<BodyResults>                                 results_;
      std::vector<std::string>                                 details_;

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
        double                 max_pressure = 0;
        double                 min_gap      = 0;
        double                 max_gap      = 0;
        double                 area         = 0;
      };

      std::vector<ObstacleParameters<dim>>    obstacle_parameters_;
      std::vector<ContactPairParameters<dim>> pair_parameters_;
      qp::SolverParameters                    qp_parameters_;
      qp::SMALSEMParameters                   smalse_parameters_;
      contact::CoulombParameters              coulomb_parameters_;
      contact::DualProblemParameters          dual_parameters_;
      bool                                    write_coulomb_iterates_ = false;
      /** Relative tolerance of the separated / stick / slip status. */
      double status_tolerance_ = 1e-6;

      std::unique_ptr<contact::ContactDiscretization<dim>>  contact_;
      std::unique_ptr<contact::DualProblem<dim>>            dual_;
      typename contact::ContactSolver<dim>::Result          contact_result_;
      double                                                qp_wall_time_ = 0;
      std::vector<std::vector<io::ContactSurfaceNode<dim>>> surfaces_;
      /** Per Coulomb iterate (if written): the surfaces of every pair. */
      std::vector<std::vector<std::vector<io::ContactSurfaceNode<dim>>>>
                               coulomb_iterates_;
      std::vector<PairResults> pair_results_;
    };
  } // namespace driver
} // namespace dualcontact
