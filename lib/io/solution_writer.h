#pragma once

#include <deal.II/lac/vector.h>

#include <fem/elastic_body.h>
#include <io/output_folder.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    /**
     * Write the displacement solutions of the bodies of a scene for
     * ParaView into @p folder:
     *  - `body_N.vtu' per body (N = 1, 2, ...): `displacement_m' (vector)
     *    and the fields of io::ElasticityPostprocessor; cells are subdivided
     *    p times for FE_Q(p) and curved with the body's mapping;
     *  - `solution.pvtu': all bodies as the pieces of one data set;
     *  - `solution.pvd': the PVD record (time 0) of solution.pvtu and of
     *    the @p additional_parts (e.g. the contact surfaces, written by the
     *    caller), each one part of the same step: the file to open in
     *    ParaView.
     *
     * Under MPI (bodies on a parallel::shared::Triangulation of more than
     * one process) every process calls this and writes the cells it owns,
     * `body_N_rank_R.vtu' (R = 0, 1, ...); process 0 writes solution.pvtu,
     * whose pieces are all of them, and solution.pvd.
     *
     * A load step of a history: @p suffix goes into the names
     * (`body_N_step_K.vtu', `solution_step_K.pvtu'), and with @p series
     * the records of this step at @p time are appended to it instead of
     * writing solution.pvd (the caller writes the series with write_pvd()).
     */
    template <int dim>
    void
    write_solution(
      OutputFolder                                              &folder,
      const std::vector<std::unique_ptr<fem::ElasticBody<dim>>> &bodies,
      const std::vector<dealii::Vector<double>>                 &displacements,
      const std::vector<std::string>              &additional_parts = {},
      const std::string                           &suffix           = "",
      const double                                 time             = 0.,
      std::vector<std::pair<double, std::string>> *series           = nullptr);
  } // namespace io
} // namespace dualcontact
