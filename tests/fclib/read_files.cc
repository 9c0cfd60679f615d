// The 8 FCLIB files of tests/fclib/data are read through libfclib with the
// sizes and friction coefficients of their README; the global ones are
// reduced to local form, and W r, q are checked against an independent
// computation (CG on M, to 1e-12) for a random r.
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <fclib/fclib_file.h>
#include <test_tools.h>

#include <algorithm>
#include <random>
#include <set>

using namespace dualcontact;
using test_tools::check;

namespace
{
  const std::string data = FCLIB_TEST_DATA_DIR;

  struct Expected
  {
    std::string      file;
    fclib::Form      form;
    unsigned int     contacts;
    unsigned int     dofs; // global only
    std::set<double> mu;
    bool             upper; // M stored as upper triangle
  };

  /** W r and q from M, H, f, w by CG on M (independent of CHOLMOD). */
  void
  check_reduction(const fclib::GlobalProblem &global,
                  const fclib::LocalProblem  &local,
                  const std::string          &name)
  {
    std::mt19937                           gen(7);
    std::uniform_real_distribution<double> dist(-1, 1);
    dealii::Vector<double>                 r(local.size()), Wr(local.size()),
      Wr_cg(local.size()), Hr(global.n_dofs()), x(global.n_dofs());
    for (auto &v : r)
      v = dist(gen);
    local.W().vmult(Wr, r);
    global.H().vmult(Hr, r);
    dealii::SolverControl control(100000, 1e-14 * Hr.l2_norm());
    dealii::SolverCG<>    cg(control);
    cg.solve(global.M(), x, Hr, dealii::PreconditionIdentity());
    global.H().Tvmult(Wr_cg, x);
    Wr_cg -= Wr;
    check(Wr_cg.l2_norm() <= 1e-10 * Wr.l2_norm(),
          name + ": ||W r - H'M^-1 H r|| / ||W r|| (CG)",
          Wr_cg.l2_norm() / Wr.l2_norm());

    dealii::Vector<double> q_cg(local.size());
    x = 0;
    dealii::SolverControl control_f(100000, 1e-14 * global.f().l2_norm());
    dealii::SolverCG<>    cg_f(control_f);
    cg_f.solve(global.M(), x, global.f(), dealii::PreconditionIdentity());
    global.H().Tvmult(q_cg, x);
    q_cg += global.w();
    q_cg -= local.q();
    check(q_cg.l2_norm() <= 1e-10 * local.q().l2_norm(),
          name + ": ||q - (H'M^-1 f + w)|| / ||q|| (CG)",
          q_cg.l2_norm() / local.q().l2_norm());
    check(local.delassus().asymmetry() <= 1e-10,
          name + ": reduced W symmetric, asymmetry",
          local.delassus().asymmetry());
  }
} // namespace

int
main()
{
  using fclib::Form;
  const std::vector<Expected> expected = {
    {"local_problem_test.hdf5", Form::local, 48, 0, {0.7}, false},
    {"Capsules-i125-1213.hdf5", Form::local, 286, 0, {0.7}, false},
    {"LMGC_100_PR_PerioBox-i00361-60-03000.hdf5",
     Form::local,
     60,
     0,
     {0.3, 0.5},
     false},
    {"CubeH8.hdf5", Form::global, 1, 162, {0.3}, true},
    {"LMGC_GlobalFrictionContactProblem00046.hdf5",
     Form::global,
     9,
     162,
     {0.3},
     true},
    {"Box_Stacks-i0122-82-5.hdf5", Form::global, 82, 450, {0.3}, false},
    {"spheres-in-a-box-98-i10000-256-10.hdf5",
     Form::global,
     256,
     588,
     {0.1},
     false},
    {"Spheres-i099-356-679.hdf5", Form::global, 356, 12000, {0.7}, false}};

  for (const Expected &e : expected)
  {
    const std::string path = data + e.file;
    const Form        form = fclib::form_of(path);
    check(form == e.form, e.file + ": form", fclib::to_string(form));
    fclib::LocalProblem local;
    if (form == Form::local)
      local = fclib::read_local(path);
    else
    {
      const fclib::GlobalProblem global = fclib::read_global(path);
      check(global.n_dofs() == e.dofs, e.file + ": dofs", global.n_dofs());
      check(global.M_was_upper_triangle() == e.upper,
            e.file + ": M stored as upper triangle",
            global.M_was_upper_triangle());
      check(global.H().m() == e.dofs && global.H().n() == 3 * e.contacts,
            e.file + ": H rows x columns",
            std::to_string(global.H().m()) + " x " +
              std::to_string(global.H().n()));
      local = global.reduce_to_local();
      check(global.factorization_name() == "cholmod",
            e.file + ": M factorized by Cholesky (SPD)",
            global.factorization_name());
      check_reduction(global, local, e.file);
    }
    check(local.spacedim() == 3, e.file + ": dimension", local.spacedim());
    check(local.n_contacts() == e.contacts,
          e.file + ": contacts",
          local.n_contacts());
    const std::set<double> mu(local.mu().begin(), local.mu().end());
    check(mu == e.mu,
          e.file + ": friction coefficients",
          std::to_string(*mu.begin()) + " .. " + std::to_string(*mu.rbegin()));
    bool finite = true;
    for (const double v : local.q())
      finite = finite && std::isfinite(v);
    check(finite && local.q().l2_norm() > 0,
          e.file + ": q finite, ||q||",
          local.q().l2_norm());
  }

  // errors name the file and say what is wrong (libfclib itself would end
  // the process on a file of the other form)
  auto message_of = [](const std::function<void()> &f) -> std::string
  {
    try
    {
      f();
    }
    catch (const dealii::ExceptionBase &e)
    {
      return fclib::exception_message(e);
    }
    return "";
  };
  const std::string wrong_form =
    message_of([&]() { fclib::read_global(data + "CubeH8.hdf5"); });
  check(wrong_form.empty(), "reading CubeH8 as global works", wrong_form);
  const std::string local_as_global =
    message_of([&]() { fclib::read_global(data + "local_problem_test.hdf5"); });
  check(local_as_global.find("holds a local problem, not a global one") !=
          std::string::npos,
        "a local file read as global",
        local_as_global);
  const std::string missing =
    message_of([&]() { fclib::read_local(data + "no_such_file.hdf5"); });
  check(missing.find("Cannot open the FCLIB file") != std::string::npos &&
          missing.find("no_such_file.hdf5") != std::string::npos,
        "a missing file",
        missing);
  const std::string not_hdf5 =
    message_of([&]() { fclib::read_local(data + "README.md"); });
  check(not_hdf5.find("is not an HDF5 file") != std::string::npos,
        "a file that is not HDF5",
        not_hdf5);
  return test_tools::finish();
}
