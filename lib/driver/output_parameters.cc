#include <deal.II/base/patterns.h>

#include <driver/output_parameters.h>
#include <fclib/scene_export.h>

namespace dualcontact
{
  namespace driver
  {
    void
    OutputParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      prm.declare_entry("Output folder",
                        "output",
                        dealii::Patterns::Anything(),
                        "Folder for the results, relative to the working "
                        "directory; created if missing. It receives "
                        "solution.pvd (open this in ParaView), solution.pvtu, "
                        "body_N.vtu, results.txt, statistics.json and "
                        "used_parameters.prm, log.txt (what the console "
                        "showed), and with contact pairs contact_N.vtu per "
                        "pair.");
      prm.declare_entry("Write VTU",
                        "true",
                        dealii::Patterns::Bool(),
                        "Whether to write the VTU/PVTU/PVD visualization "
                        "files (the other files are always written).");
      prm.declare_entry("Write Coulomb iterates",
                        "false",
                        dealii::Patterns::Bool(),
                        "With Coulomb friction: also write the contact "
                        "surfaces of every fixed-point iterate "
                        "(contact_N_iterate_K.vtu) and coulomb_iterates.pvd, "
                        "a series over the iterates (time = iterate number).");
      prm.declare_entry("Contact status tolerance",
                        "1e-6",
                        dealii::Patterns::Double(0., 1.),
                        "Relative tolerance [-] of the status written per "
                        "contact node: separated if lambda_N <= tolerance * "
                        "max lambda_N of the pair, slip if the tangential "
                        "multiplier reaches (1 - tolerance) times its slip "
                        "bound (the boundary of the friction set), stick "
                        "otherwise; frictionless nodes in contact count as "
                        "slip.");
      prm.declare_entry(
        "Verbosity",
        "normal",
        dealii::Patterns::Selection("quiet|normal|detailed"),
        "What the console shows (process 0). quiet: nothing but errors. "
        "normal: a line per phase with its wall time (a phase that runs "
        "long shows its start first), the phases' details, during the long "
        "phases (factorization, QP, Coulomb fixed point, refinement cycles) "
        "a progress line every `Progress interval' seconds, the results, "
        "and a timing table at the end. detailed: also a progress line at "
        "the start of every QP solve and after every Coulomb iterate, and "
        "every phase's start. log.txt in the output folder always holds "
        "the normal (or detailed) console, also for quiet runs.");
      prm.declare_entry("Progress interval",
                        "5",
                        dealii::Patterns::Double(0.1),
                        "Seconds [s] between two progress lines of a long "
                        "solve (QP iterations with the criterion against "
                        "its tolerance, the active set, Hessian products "
                        "and the time).");
      prm.declare_entry("FCLIB problem",
                        "none",
                        dealii::Patterns::Selection(
                          fclib::export_form_names.choices()),
                        "Scenes with contact pairs: also write the contact "
                        "problem as a Frictional Contact Library (FCLIB, "
                        "HDF5) file with the solution found (/solution): "
                        "global = contact_problem_global.hdf5 (M = K, H = "
                        "-B', f, w = gaps, mu), local = "
                        "contact_problem_local.hdf5 (W = F, q = -d, mu), "
                        "both, or none. Only frictionless and isotropic "
                        "Coulomb pairs, and no floating bodies (see "
                        "doc/fclib.md).");
      prm.leave_subsection();
    }


    void
    OutputParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      folder                   = prm.get("Output folder");
      write_vtu                = prm.get_bool("Write VTU");
      write_coulomb_iterates   = prm.get_bool("Write Coulomb iterates");
      contact_status_tolerance = prm.get_double("Contact status tolerance");
      verbosity                = prm.get("Verbosity");
      progress_interval        = prm.get_double("Progress interval");
      fclib_problem            = prm.get("FCLIB problem");
      prm.leave_subsection();
    }
  } // namespace driver
} // namespace dualcontact
