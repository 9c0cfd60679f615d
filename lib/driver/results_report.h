#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <driver/contact_refinement.h>
#include <driver/contact_stage.h>
#include <driver/scene.h>
#include <io/output_folder.h>

#include <string>
#include <utility>
#include <vector>

namespace dualcontact
{
  namespace driver
  {
    /**
     * What a run writes, from a Scene and (scenes with contact pairs) its
     * ContactStage: the VTU/PVTU/PVD files of the bodies and contact
     * surfaces, results.txt (the numbers reference tests compare),
     * statistics.json (timings, solver records) and used_parameters.prm.
     * Everything goes through an io::OutputFolder, which renames the files
     * to their final names only when all are written.
     */
    template <int dim>
    class ResultsReport
    {
    public:
      /** @p contact is null for a scene without contact pairs. */
      ResultsReport(const Scene<dim>        &scene,
                    const ContactStage<dim> *contact,
                    const std::string       &parameter_file);

      /**
       * The VTU/PVTU/PVD files (bodies if @p write_vtu, contact always).
       * Under MPI every process calls this and writes its pieces: of every
       * body (io::write_solution) and of every contact surface
       * (contact_N_rank_R.vtu, the slave faces of the cells it owns);
       * process 0 also writes the records (solution.pvtu, contact_N.pvtu,
       * and solution.pvd listing solution.pvtu and the contact surfaces), the
       * Coulomb iterates (whole) and the records.
       */
      /**
       * A load step of a history: @p suffix in every name (`_step_K'), and
       * with @p series the step's records at @p time appended to it
       * instead of solution.pvd (io::write_solution).
       */
      void
      write_output(
        io::OutputFolder                            &folder,
        const bool                                   write_vtu,
        const std::string                           &suffix = "",
        const double                                 time   = 0.,
        std::vector<std::pair<double, std::string>> *series = nullptr) const;

      /**
       * The scene's contact problem as FCLIB file(s) (`Output/FCLIB
       * problem` = @p form: global, local or both; lib/fclib), with the
       * solution if the contact solver converged.  One process only.
       */
      void
      write_fclib_problem(io::OutputFolder  &folder,
                          const std::string &form) const;

      /**
       * results.txt, statistics.json (with the phase times of @p timer),
       * used_parameters.prm (@p prm); the caller commits @p folder (after
       * log.txt).
       */
      void
      write_records(io::OutputFolder               &folder,
                    const dealii::ParameterHandler &prm,
                    const dealii::TimerOutput      &timer) const;

      /**
       * The solves of a contact refinement loop (ContactRefinement), one
       * record per cycle, written as `refinement.*' to results.txt and
       * statistics.json; null or empty (no refinement): nothing written.
       */
      void
      set_refinement_cycles(
        const std::vector<typename ContactRefinement<dim>::CycleRecord> *cycles)
      {
        cycles_ = cycles;
      }

      /**
       * Whether results.txt has the energy dissipated by friction
       * (`pair_N.dissipated_energy', `total.dissipated_energy'
       * [J, J/m in 2D], ContactStage::dissipated_energy()): a load history.
       */
      void
      set_dissipated_energy(const bool with_dissipation)
      {
        with_dissipation_ = with_dissipation;
      }

      /** The text of results.txt. */
      std::string
      results_text() const;
      /** The text of statistics.json. */
      std::string
      statistics_json(const dealii::TimerOutput &timer) const;

    private:
      const Scene<dim>        &scene_;
      const ContactStage<dim> *contact_;
      const std::string        parameter_file_;
      const std::vector<typename ContactRefinement<dim>::CycleRecord> *cycles_ =
        nullptr;
      bool with_dissipation_ = false;
    };
  } // namespace driver
} // namespace dualcontact
