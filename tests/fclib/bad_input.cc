// fclibsolve's bad input (issue 15): every option value is checked (`--max-iter
// -1' and `--tol -5' were taken for "the default"); a truncated HDF5 file is
// reported as truncated or corrupt in one line naming the file (it was "holds
// neither /fclib_local nor /fclib_global"), without HDF5's error stack on
// stderr; --write goes through a temporary file that replaces the old one.
#include <fclib/fclib_file.h>
#include <test_tools.h>
#include <tools/fclibsolve_driver.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace dualcontact;

namespace
{
  struct Run
  {
    int         status;
    std::string out;
    std::string err;
    std::string stderr_text; ///< what went to file descriptor 2 directly
  };

  /** fclibsolve ARGS, with file descriptor 2 captured (HDF5 prints there). */
  Run
  fclibsolve(const std::vector<std::string> &arguments)
  {
    const std::string captured = "bad_input_stderr.txt";
    std::fflush(stderr);
    const int saved = dup(2);
    FILE     *file  = std::fopen(captured.c_str(), "w");
    dup2(fileno(file), 2);
    std::ostringstream out, err;
    const int status = tools::FclibSolveDriver().run(arguments, out, err);
    std::fflush(stderr);
    dup2(saved, 2);
    close(saved);
    std::fclose(file);
    std::ifstream      in(captured);
    std::ostringstream text;
    text << in.rdbuf();
    std::filesystem::remove(captured);
    return {status, out.str(), err.str(), text.str()};
  }

  void
  check(const bool ok, const std::string &what)
  {
    test_tools::check(ok, what, ok ? "as expected" : "not as expected");
  }

  bool
  contains(const std::string &text, const std::string &part)
  {
    const bool found = text.find(part) != std::string::npos;
    if (!found)
      std::cout << "      output: " << text.substr(0, 800) << std::endl;
    return found;
  }
} // namespace


int
main()
{
  const std::string data = FCLIB_TEST_DATA_DIR "local_problem_test.hdf5";

  for (const auto &[option, value, expected] :
       std::vector<std::array<std::string, 3>>{
         {{"--max-iter", "-1", "--max-iter must be an integer in [1, "}},
         {{"--max-iter", "1e30", "--max-iter: '1e30' is not an integer"}},
         {{"--coulomb-max-iter", "0", "--coulomb-max-iter must be an integer"}},
         {{"--tol", "-5", "--tol must be > 0 (got -5)"}},
         {{"--tol", "nan", "--tol: 'nan' is not a number"}},
         {{"--coulomb-tol", "0", "--coulomb-tol must be > 0 (got 0)"}}})
  {
    const Run run = fclibsolve({data, option, value});
    check(run.status == 1 && contains(run.err, expected),
          "fclibsolve " + option + " " + value + " is refused");
  }

  // the .prm names (issue 18): `--set' with the names of subsections `QP
  // solver' and `Coulomb'; bad entries and values are named, and checked as
  // the options are
  for (const auto &[setting, expected] :
       std::vector<std::array<std::string, 2>>{
         {{"Coulomb/Tolerence=1e-6", "Tolerence"}},
         {{"QP solver/Solver=newton", "newton"}},
         {{"Coulomb/Maximum iterations=-3", "Maximum iterations"}},
         {{"QP solver/Tolerance=-5", "olerance"}}})
  {
    const Run run = fclibsolve({data, "--set", setting});
    check(run.status == 1 && contains(run.err, expected),
          "fclibsolve --set \"" + setting + "\" is refused naming it");
  }
  {
    const Run run = fclibsolve({data,
                                "--set",
                                "QP solver/Solver=spg-qp",
                                "--set",
                                "Coulomb/Tolerance=1e-6"});
    check(run.status == 0 && contains(run.out, "spg-qp"),
          "fclibsolve --set \"QP solver/Solver=spg-qp\" solves with spg-qp");
  }

  // a file cut in half: one line naming the file, nothing from HDF5
  const std::string truncated = "bad_input_truncated.hdf5";
  {
    std::ifstream in(data, std::ios::binary);
    std::string   bytes((std::istreambuf_iterator<char>(in)),
                      std::istreambuf_iterator<char>());
    std::ofstream(truncated, std::ios::binary)
      << bytes.substr(0, bytes.size() / 2);
  }
  {
    const Run run = fclibsolve({truncated});
    check(run.status == 1 &&
            contains(run.err,
                     "fclibsolve: `" + truncated +
                       "' is a truncated or corrupt HDF5 file") &&
            std::count(run.err.begin(), run.err.end(), '\n') == 1,
          "a truncated file: one line saying truncated or corrupt");
    check(run.stderr_text.empty(), "no HDF5 error stack on stderr");
    if (!run.stderr_text.empty())
      std::cout << run.stderr_text.substr(0, 400) << std::endl;
  }
  std::filesystem::remove(truncated);

  // --write replaces an existing file through a temporary one
  const std::string written = "bad_input_written.hdf5";
  std::ofstream(written) << "an older file\n";
  {
    const Run run = fclibsolve({data, "--write", written});
    check(run.status == 0 && fclib::form_of(written) == fclib::Form::local &&
            fclib::read_local(written).size() == 144,
          "--write replaces the existing file with the problem");
    bool temporary_left = false;
    for (const auto &entry : std::filesystem::directory_iterator("."))
      temporary_left = temporary_left || entry.path().filename().string().find(
                                           written + ".") == 0;
    check(!temporary_left, "--write leaves no temporary file");
  }
  std::filesystem::remove(written);
  return test_tools::finish();
}
