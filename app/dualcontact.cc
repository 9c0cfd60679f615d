// dualcontact: multi-body linear elasticity with frictional contact,
// driven by a parameter file.  Thin: all work is in lib/driver and below.

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <util/blas_kernels.h>

#include <driver/parameter_reference.h>
#include <driver/scene_parameters.h>
#include <driver/simulation.h>
#include <io/console_log.h>
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
      << "Usage: dualcontact FILE.prm [--set \"Subsection/Entry=value\"]... "
         "[--validate]\n"
         "       dualcontact --print-parameters[=prm|json]\n"
         "       dualcontact --help | --version\n"
         "\n"
         "Computes the scene described in the parameter file FILE.prm "
         "(deal.II\n"
         "ParameterHandler format: `set Name = value' lines grouped in\n"
         "`subsection ... end' blocks) and writes the results into the folder\n"
         "named by `set Output folder' in `subsection Output'.\n"
         "\n"
         "  --set \"Subsection/Entry=value\"\n"
         "                      set a parameter after reading FILE.prm, as a\n"
         "                      `set Entry = value' line at its end would\n"
         "                      (nested subsections separated by `/', e.g.\n"
         "                      --set \"Body 1/Mesh/Global refinements=3\");\n"
         "                      repeatable; checked like the file's values\n"
         "  --validate          check the input (parameters, files, meshes,\n"
         "                      boundary and material ids) and print the\n"
         "                      scene: bodies, cells, dofs, contact pairs,\n"
         "                      solvers; computes and writes nothing\n"
         "  --print-parameters  print every parameter with its default, its\n"
         "                      allowed values and its documentation, as a\n"
         "                      parameter file (one body; `Body 2', ... work\n"
         "                      the same way)\n"
         "  --print-parameters=json\n"
         "                      the same as JSON (machine-readable: every\n"
         "                      subsection, entry, default, pattern and\n"
         "                      documentation; scripts/parameter_reference\n"
         "                      makes the manual's reference from it)\n"
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


/** What the command line asks for. */
struct CommandLine
{
  std::string                                     parameter_file;
  std::vector<dualcontact::io::ParameterOverride> overrides;
  bool                                            validate = false;
};


/**
 * FILE.prm, --set "A/B=v" (or --set=A/B=v) and --validate in any order;
 * throws an ExcMessage for anything else.
 */
CommandLine
parse_command_line(const std::vector<std::string> &arguments)
{
  CommandLine command_line;
  for (unsigned int k = 0; k < arguments.size(); ++k)
  {
    const std::string &argument = arguments[k];
    if (argument == "--set")
    {
      AssertThrow(
        k + 1 < arguments.size(),
        dealii::ExcMessage(
          "`--set' needs a value: --set \"Subsection/Entry=value\"."));
      command_line.overrides.push_back(
        dualcontact::io::parse_parameter_override(arguments[++k]));
    }
    else if (argument.rfind("--set=", 0) == 0)
      command_line.overrides.push_back(
        dualcontact::io::parse_parameter_override(argument.substr(6)));
    else if (argument == "--validate")
      command_line.validate = true;
    else if (!argument.empty() && argument[0] == '-')
    {
      AssertThrow(false,
                  dealii::ExcMessage("Unknown option `" + argument +
                                     "' (see `dualcontact --help')."));
    }
    else
    {
      AssertThrow(command_line.parameter_file.empty(),
                  dealii::ExcMessage("Two parameter files given, `" +
                                     command_line.parameter_file + "' and `" +
                                     argument +
                                     "': dualcontact computes one scene."));
      command_line.parameter_file = argument;
    }
  }
  AssertThrow(!command_line.parameter_file.empty(),
              dealii::ExcMessage("No parameter file given (see `dualcontact "
                                 "--help')."));
  return command_line;
}


int
main(int argc, char *argv[])
{
  // OpenBLAS' fast kernels on CPUs it does not recognise
  (void)dualcontact::util::blas_kernel_choice();
  using namespace dualcontact;
  bool is_rank_0 = true;
  try
  {
    dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
    is_rank_0 = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    // what the console shows is kept for log.txt
    io::ConsoleLog             log(std::cout);
    dealii::ConditionalOStream console(log.stream(), is_rank_0);

    const std::vector<std::string> arguments(argv + 1, argv + argc);
    if (arguments.empty())
    {
      if (is_rank_0)
      {
        std::cerr << "dualcontact: expected a parameter file.\n\n";
        print_help(std::cerr);
      }
      return 1;
    }
    const std::string &argument = arguments.front();
    if (arguments.size() == 1 && (argument == "--help" || argument == "-h"))
    {
      if (is_rank_0)
        print_help(std::cout);
      return 0;
    }
    if (arguments.size() == 1 && argument == "--version")
    {
      if (is_rank_0)
        std::cout << "dualcontact " << DUALCONTACT_VERSION << std::endl;
      return 0;
    }
    if (arguments.size() == 1 &&
        (argument == "--print-parameters" ||
         argument.rfind("--print-parameters=", 0) == 0))
    {
      const auto format =
        argument == "--print-parameters" ?
          driver::ParameterReference::Format::prm :
          driver::ParameterReference::parse_format(argument.substr(19));
      if (is_rank_0)
        driver::ParameterReference::print(std::cout, format);
      return 0;
    }

    const CommandLine  command_line = parse_command_line(arguments);
    const std::string &file         = command_line.parameter_file;
    console << "dualcontact " << DUALCONTACT_VERSION << ": " << file
            << std::endl;
    io::OutputFolder::install_signal_handlers();
    for (const auto &entry : command_line.overrides)
      console << "  --set " << entry.text << std::endl;
    driver::SceneLayout layout;
    const auto          prm =
      driver::SceneParameters::read(file, layout, command_line.overrides);
    if (command_line.validate)
    {
      if (layout.dimension == 2)
        driver::Simulation<2>(*prm, file, console, &log).validate();
      else
        driver::Simulation<3>(*prm, file, console, &log).validate();
      return 0;
    }
    // exit code 2: the contact solver did not converge (output written)
    const bool converged =
      layout.dimension == 2 ?
        driver::Simulation<2>(*prm, file, console, &log).run() :
        driver::Simulation<3>(*prm, file, console, &log).run();
    if (!converged)
      return 2;
  }
  // Every process reads the same input and runs the same phases, so every
  // process meets the same error: process 0 says it, all exit with 1.
  catch (const std::exception &exception)
  {
    if (is_rank_0)
      std::cerr << "\nError: " << message_of(exception) << std::endl;
    return 1;
  }
  catch (...)
  {
    if (is_rank_0)
      std::cerr << "\nError: unknown exception." << std::endl;
    return 1;
  }
  return 0;
}
