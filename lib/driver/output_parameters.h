/**
 * @file output_parameters.h
 * Subsection `Output' of the parameter file, read once (by Simulation) into
 * a const struct that the run log, the contact stage and the report share.
 */
#ifndef dualcontact_driver_output_parameters_h
#define dualcontact_driver_output_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace dualcontact
{
  namespace driver
  {
    /** Subsection `Output'. */
    struct OutputParameters
    {
      /** Folder for the results, relative to the working directory. */
      std::string folder = "output";
      /** Whether to write the VTU/PVTU/PVD files. */
      bool write_vtu = true;
      /** Coulomb: also the contact surfaces of every fixed-point iterate. */
      bool write_coulomb_iterates = false;
      /** Relative tolerance [-] of the separated / stick / slip status. */
      double contact_status_tolerance = 1e-6;
      /** quiet | normal | detailed */
      std::string verbosity = "normal";
      /** Seconds [s] between two progress lines of a long solve. */
      double progress_interval = 5.;
      /** none | global | local | both: the FCLIB file(s) to write. */
      std::string fclib_problem = "none";

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace driver
} // namespace dualcontact

#endif
