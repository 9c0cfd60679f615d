// FCLIB files whose headers do not fit their data (issue 15: readers check
// sizes against the file before allocating).  libfclib allocates every
// array from a matrix's header (m, n, nz, nzmax) and reads the whole data
// set into it: a header smaller than the data overflowed the heap, a huge
// one allocated before reading.  Each damaged copy below is refused by
// fclib::FileLayout (or, for the pointer values, by the reader), with a
// message naming the file and the data set, and fclibsolve exits with 1;
// the undamaged files of tests/fclib/data still read, with their
// solutions.
#include <fclib/fclib_file.h>
#include <fclib/file_layout.h>
#include <test_tools.h>
#include <tools/fclibsolve_driver.h>

#include <hdf5.h>

#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

using namespace dualcontact;

namespace
{
  /** Replaces (or adds) the data set @p name of @p path by @p values. */
  template <typename Number>
  void
  write_data_set(const std::string         &path,
                 const std::string         &name,
                 const std::vector<Number> &values)
  {
    const bool  is_int = std::is_integral_v<Number>;
    const hid_t file   = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    if (H5Lexists(file, name.c_str(), H5P_DEFAULT) > 0)
      H5Ldelete(file, name.c_str(), H5P_DEFAULT);
    const hsize_t size  = values.size();
    const hid_t   space = H5Screate_simple(1, &size, nullptr);
    const hid_t   set   = H5Dcreate2(file,
                                 name.c_str(),
                                 is_int ? H5T_STD_I32LE : H5T_IEEE_F64LE,
                                 space,
                                 H5P_DEFAULT,
                                 H5P_DEFAULT,
                                 H5P_DEFAULT);
    H5Dwrite(set,
             is_int ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE,
             H5S_ALL,
             H5S_ALL,
             H5P_DEFAULT,
             values.data());
    H5Dclose(set);
    H5Sclose(space);
    H5Fclose(file);
  }

  /** The int data set @p name of @p path. */
  std::vector<int>
  read_ints(const std::string &path, const std::string &name)
  {
    const hid_t      file  = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t      set   = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
    const hid_t      space = H5Dget_space(set);
    std::vector<int> values(H5Sget_simple_extent_npoints(space));
    H5Dread(set, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Sclose(space);
    H5Dclose(set);
    H5Fclose(file);
    return values;
  }

  void
  add_group(const std::string &path, const std::string &name)
  {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    H5Gclose(
      H5Gcreate2(file, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    H5Fclose(file);
  }

  struct Damage
  {
    std::string                              source; ///< file of data/
    std::string                              what;
    std::function<void(const std::string &)> apply;
    std::string                              expected; ///< in the message
  };
} // namespace


int
main()
{
  const std::string local  = "local_problem_test.hdf5";
  const std::string global = "LMGC_GlobalFrictionContactProblem00046.hdf5";
  const std::string W = "/fclib_local/W/", H = "/fclib_global/H/";

  const std::vector<Damage> damages{
    {local,
     "W/nzmax smaller than W/i and W/x (the heap overflow)",
     [&](const std::string &f) { write_data_set<int>(f, W + "nzmax", {10}); },
     "/fclib_local/W/i holds 4896 entries, /fclib_local/W/nzmax says 10"},
    {local,
     "W/nzmax of 10^9 (the allocation before reading)",
     [&](const std::string &f)
     { write_data_set<int>(f, W + "nzmax", {1000000000}); },
     "/fclib_local/W/i holds 4896 entries, /fclib_local/W/nzmax says "
     "1000000000"},
    {local,
     "W/m larger than its row pointers",
     [&](const std::string &f) { write_data_set<int>(f, W + "m", {150}); },
     "/fclib_local/W/p holds 145 entries, m + 1 (compressed rows) says 151"},
    {local,
     "W/nz of no storage",
     [&](const std::string &f) { write_data_set<int>(f, W + "nz", {-3}); },
     "/fclib_local/W/nz is -3: neither triplets"},
    {local,
     "W/m negative",
     [&](const std::string &f) { write_data_set<int>(f, W + "m", {-144}); },
     "/fclib_local/W has -144 x 144 entries"},
    {local,
     "q shorter than W's order",
     [&](const std::string &f)
     {
       write_data_set<double>(f,
                              "/fclib_local/vectors/q",
                              std::vector<double>(100, 1.));
     },
     "/fclib_local/vectors/q holds 100 entries, the order of W says 144"},
    {local,
     "mu of one contact too few",
     [&](const std::string &f)
     {
       write_data_set<double>(f,
                              "/fclib_local/vectors/mu",
                              std::vector<double>(47, 0.5));
     },
     "/fclib_local/vectors/mu holds 47 entries, the number of contacts says "
     "48"},
    {local,
     "a row pointer past nzmax",
     [&](const std::string &f)
     {
       auto p = read_ints(f, W + "p");
       p[5]   = 1000000;
       write_data_set<int>(f, W + "p", p);
     },
     "row pointers: pointer 5 is 1000000"},
    {local,
     "equality constraints V",
     [&](const std::string &f) { add_group(f, "/fclib_local/V"); },
     "/fclib_local/V is present: local problems with equality constraints"},
    {local,
     "a solution of the wrong size",
     [&](const std::string &f)
     { write_data_set<double>(f, "/solution/r", std::vector<double>(10, 0.)); },
     "/solution/r holds 10 entries, the number of contact unknowns says 144"},
    {global,
     "H with fewer rows than M",
     [&](const std::string &f) { write_data_set<int>(f, H + "m", {100}); },
     "/fclib_global/H has 100 rows, M has 162"},
    {global,
     "H/nz larger than its triplets",
     [&](const std::string &f)
     {
       write_data_set<int>(f, H + "nz", {500});
       write_data_set<int>(f, H + "nzmax", {500});
     },
     "/fclib_global/H/p holds 405 entries, /fclib_global/H/nz (triplets) "
     "says 500"},
    {global,
     "equality constraints G",
     [&](const std::string &f) { add_group(f, "/fclib_global/G"); },
     "/fclib_global/G is present: global problems with equality"},
    {global,
     "space dimension 4",
     [&](const std::string &f)
     { write_data_set<int>(f, "/fclib_global/spacedim", {4}); },
     "/fclib_global/spacedim is 4, not 2 or 3"}};

  for (const auto &damage : damages)
  {
    const std::string copy = "damaged_" + damage.source;
    std::filesystem::copy_file(
      FCLIB_TEST_DATA_DIR + damage.source,
      copy,
      std::filesystem::copy_options::overwrite_existing);
    damage.apply(copy);

    std::string message;
    try
    {
      fclib::read_as_local(copy);
      if (damage.what.find("solution") != std::string::npos)
        fclib::read_solution_r(copy);
    }
    catch (const dealii::ExceptionBase &e)
    {
      message = fclib::exception_message(e);
    }
    const bool named = message.find("`" + copy + "'") != std::string::npos &&
                       message.find(damage.expected) != std::string::npos;
    test_tools::check(named,
                      damage.what + ": refused naming the file and data set",
                      message.empty() ? "(read without error)" : message);

    std::ostringstream out, err;
    const int          status = tools::FclibSolveDriver().run({copy}, out, err);
    test_tools::check(status == 1 &&
                        err.str().find(damage.expected) != std::string::npos,
                      damage.what + ": fclibsolve exits with 1",
                      status);
    std::filesystem::remove(copy);
  }

  // every distributed file still reads, with its layout and solution
  for (const auto &entry :
       std::filesystem::directory_iterator(FCLIB_TEST_DATA_DIR))
  {
    if (entry.path().extension() != ".hdf5")
      continue;
    const std::string path = entry.path().string();
    std::string       text;
    bool              ok = true;
    try
    {
      const fclib::Form        form = fclib::form_of(path);
      const fclib::FileLayout  layout(path, form);
      const unsigned long long size = form == fclib::Form::local ?
                                        fclib::read_local(path).size() :
                                        fclib::read_global(path).H().n();
      const auto               r    = fclib::read_solution_r(path);
      ok = size == layout.contact_size() && (r.size() == 0 || r.size() == size);
      text = std::to_string(size) + " contact unknowns, solution of " +
             std::to_string(r.size());
    }
    catch (const dealii::ExceptionBase &e)
    {
      ok   = false;
      text = fclib::exception_message(e);
    }
    test_tools::check(ok, entry.path().filename().string() + " reads", text);
  }
  return test_tools::finish();
}
