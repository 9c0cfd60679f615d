// dualcontact: multi-body linear elasticity with frictional contact,
// driven by a parameter file.  Thin: all work is in lib/driver and below.

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <util/blas_kernels.h>

#include <driver/scene_parameters.h>
#include <driver/simulation.h>
#include <io/output_folder.h>
#include <io/parameter_file.h>

#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  void
  print_help(std::ostream &out)
  {
    out
      << "Usage: dualcontact FILE.prm\n"
         "       dualcontact --print-parameters\n"
         "       dualcontact --help | --version\n"
         "\n"
         "Computes the scene described in the parameter file FILE.prm "
         "(deal.II\n"
         "ParameterHandler format: `set Name = value' lines grouped in\n"
         "`subsection ... end' blocks) and writes the results into the folder\n"
         "named by `set Output folder' in `subsection Output'.\n"
         "\n"
         "  --print-parameters  print every parameter with its default, its\n"
         "                      allowed values and its documentation, as a\n"
         "                      parameter file (one body; `Body 2', ... work\n"
         "                      the same way)\n"
         "  --help              this text\n"
         "  --version           the version\n"
         "\n"
         "Examples are in inputs/ of the source tree (inputs/default.prm).\n";
  }

  /** The message of an exception without deal.II's source location. */
  std::string
  message_of(const std::exception &exception)
  {
    if (const auto *deal_exception =
          dynamic_cast<const dealii::ExceptionBase *>(&exception))
    {
      std::ostringstream info;
      deal_exception->print_info(info);
      const std::string text = dealii::Utilities::trim(info.str());
      if (!text.empty())
        return text;
    }
    return exception.what();
  }
} // namespace


int
main(int argc, char *argv[])
{
  // OpenBLAS' fast kernels on CPUs it does not recognise
  (void)dualcontact::util::blas_kernel_choice();
  using namespace dualcontact;
  try
  {
    dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
    const bool                               is_rank_0 =
      dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    dealii::ConditionalOStream console(std::cout, is_rank_0);

    const std::vector<std::string> arguments(argv + 1, argv + argc);
    if (arguments.size() != 1)
    {
      if (is_rank_0)
      {
        std::cerr << "dualcontact: expected one argument.\n\n";
        print_help(std::cerr);
      }
      return 1;
    }
    const std::string &argument = arguments.front();
    if (argument == "--help" || argument == "-h")
    {
      if (is_rank_0)
        print_help(std::cout);
      return 0;
    }
    if (argument == "--version")
    {
      console << "dualcontact " << DUALCONTACT_VERSION << std::endl;
      return 0;
    }
    if (argument == "--print-parameters")
    {
      dealii::ParameterHandler prm;
      driver::SceneLayout      layout;
      layout.n_obstacles     = 1;
      layout.n_contact_pairs = 1;
      driver::SceneParameters::declare_parameters(prm, layout);
      if (is_rank_0)
      {
        std::cout << "# dualcontact " << DUALCONTACT_VERSION
                  << ": all parameters, with documentation, default "
                     "and allowed values.\n# Shown for one body, one "
                     "obstacle and one contact pair; `Body 2', `Obstacle "
                     "2', `Contact pair 2', ... have the same entries.\n\n";
        io::print_documented_parameters(prm, std::cout);
      }
      return 0;
    }
    if (!argument.empty() && argument[0] == '-')
    {
      if (is_rank_0)
      {
        std::cerr << "dualcontact: unknown option `" << argument << "'.\n\n";
        print_help(std::cerr);
      }
      return 1;
    }

    console << "dualcontact " << DUALCONTACT_VERSION << ": " << argument
            << std::endl;
    io::OutputFolder::install_signal_handlers();
    driver::SceneLayout layout;
    const auto          prm = driver::SceneParameters::read(argument, layout);
    // exit code 2: the contact solver did not converge (output written)
    const bool converged =
      layout.dimension == 2 ?
        driver::Simulation<2>(*prm, argument, console).run() :
        driver::Simulation<3>(*prm, argument, console).run();
    if (!converged)
      return 2;
  }
  catch (const std::exception &exception)
  {
    std::cerr << "\nError: " << message_of(exception) << std::endl;
    return 1;
  }
  catch (...)
  {
    std::cerr << "\nError: unknown exception." << std::endl;
    return 1;
  }
  return 0;
}
