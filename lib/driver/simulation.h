#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <driver/body_parameters.h>
#include <fem/elastic_body.h>
#include <fem/stiffness_solver.h>
#include <io/output_folder.h>

#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace driver
  {
    /**
     * One run of a scene of elastic bodies (no contact yet): meshes, setup,
     * assembly, one stiffness solve per body, derived results, output.
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

      void
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
    };
  } // namespace driver
} // namespace dualcontact
