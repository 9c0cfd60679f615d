#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <driver/contact_refinement.h>
#include <driver/contact_stage.h>
#include <driver/load_steps.h>
#include <driver/output_parameters.h>
#include <driver/run_log.h>
#include <driver/scene.h>
#include <io/console_log.h>
#include <io/output_folder.h>

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
     * Console output goes to @p console (rank 0 only under MPI) through a
     * RunLog: each phase prints one line with its wall time, long phases
     * progress lines, the end a TimerOutput table; `Output/Verbosity'
     * chooses how much, and log.txt in the output folder keeps it.
     *
     * The work is in Scene (bodies: meshes, assembly, solve, per-body
     * results), ContactStage (contact search, dual problem, QP, recovery,
     * contact surfaces) and ResultsReport (the files written); this class
     * runs the phases and prints the log.  With `Contact refinement/Cycles'
     * > 0 it repeats Setup .. Postprocessing on meshes refined at the
     * contact zone by ContactRefinement (a Refinement phase before each
     * repeat); the output is the last solve's.
     */
    template <int dim>
    class Simulation
    {
    public:
      /**
       * @p console prints on process 0; @p log (may be null) is the stream
       * behind it, whose text is written as log.txt with the output and
       * whose terminal `Output/Verbosity = quiet' switches off.
       */
      Simulation(dealii::ParameterHandler   &prm,
                 const std::string          &parameter_file,
                 dealii::ConditionalOStream &console,
                 io::ConsoleLog             *log = nullptr);
      ~Simulation();

      /**
       * Run the scene and write its output.  Returns false if the contact
       * solver did not converge: the output is written all the same
       * (flagged as not converged in results.txt and statistics.json), so
       * that a failed run can be inspected; the program then exits with 2.
       */
      bool
      run();

      /**
       * Check the scene as far as it can be without computing: the
       * parameters (done by the constructor), the meshes (cells, boundary
       * and material ids of every condition and pair) and the dofs; then
       * print its summary (bodies with cells and dofs, contact pairs,
       * solvers).  Assembles, solves and writes nothing.
       */
      void
      validate();

    private:
      /**
       * Throw (on every process) if a displacement, a multiplier or a
       * contact result is not finite (NaN or inf): such a result is an
       * error with nothing written, never "Output written".  The loads are
       * checked finite during assembly; this catches what overflows in the
       * solve (extreme materials, loads or geometry).
       */
      void
      check_finite_results() const;

      /**
       * With `FCLIB problem' set: throw naming the body if a body of
       * @p scene has rigid-body motions its Dirichlet conditions do not
       * hold (after the setup, before assembly and solve; a body without
       * any Dirichlet condition is refused when the scene is read).
       */
      void
      check_fclib_bodies_held(const Scene<dim> &scene) const;

      /** Why the contact solver did not converge, with its residuals. */
      std::string
      failure_message() const;

      /**
       * The load steps of one cycle on the set-up, assembled (and, with
       * contact, factorized) scene: per step the loads at its time, the
       * solve, the postprocessing; a step that does not converge ends the
       * history (failed_step_).
       */
      void
      run_load_steps();
      /** QP and Recovery (or Solve), Postprocessing of step @p step. */
      void
      solve_step(const unsigned int step);
      /**
       * One row of history.csv for step @p step: the step, its time, and
       * results.txt's forces (a vector's components as KEY.x, KEY.y,
       * KEY.z), counts, areas and the dissipated energy.
       */
      void
      record_history_row(const unsigned int step);
      /** The console line of a load step: time, QP iterations, Coulomb
       *  iterates, stick / slip counts. */
      std::string
      step_line(const unsigned int step) const;

      /** The scene line: dimension, bodies, element, solvers. */
      void
      print_scene_line();

      /** Run @p phase timed, then print its line and the details lines. */
      template <typename Phase>
      void
      run_phase(const std::string &name, const Phase &phase);
      /**
       * Console lines (details of the current phase) with the nominal and
       * the applied resultant of every traction condition, and a warning
       * where they differ by more than traction_warning_threshold.
       */
      void
      report_traction_resultants(const Scene<dim> &scene);

      /** Relative difference of applied and nominal traction resultant
       * above which the console warns [-]. */
      static constexpr double traction_warning_threshold = 1e-3;
      /**
       * A warning line for every body whose forces do not balance
       * (ElasticBody::Summary::force_imbalance above
       * force_balance_warning_threshold).
       */
      void
      report_force_balance(const Scene<dim> &scene);
      /** Relative force imbalance of a body above which the console warns
       *  [-]: an equilibrium solve leaves round-off, 1e-12 and below. */
      static constexpr double force_balance_warning_threshold = 1e-8;

      dealii::ParameterHandler   &prm_;
      const std::string           parameter_file_;
      dealii::ConditionalOStream &console_;
      RunLog                      run_log_;
      const bool                  is_output_rank_;
      dealii::TimerOutput         timer_;

      /** Subsection `Load steps', read once. */
      LoadSteps load_steps_;
      /** history.csv: its columns and one row per step computed. */
      std::vector<std::string>              history_header_;
      std::vector<std::vector<std::string>> history_rows_;
      /** solution.pvd of a history: the records of every step. */
      std::vector<std::pair<double, std::string>> pvd_series_;
      /** The step that did not converge (-1: none). */
      int failed_step_ = -1;
      /** Subsection `Output', read once. */
      const OutputParameters output_;
      /** OpenBLAS' threads and why ("2 (automatic: load average ...)"). */
      std::string                       blas_threads_;
      std::unique_ptr<io::OutputFolder> output_folder_;
      std::unique_ptr<Scene<dim>>       scene_;
      /** Null for a scene without contact pairs. */
      std::unique_ptr<ContactStage<dim>> contact_;
      /** Subsection `Contact refinement' (0 cycles: one solve). */
      std::unique_ptr<ContactRefinement<dim>> refinement_;
      /** Per solve of the refinement loop (empty without refinement). */
      std::vector<typename ContactRefinement<dim>::CycleRecord> cycles_;
      /** The console lines of the current phase. */
      std::vector<std::string> details_;
    };
  } // namespace driver
} // namespace dualcontact
