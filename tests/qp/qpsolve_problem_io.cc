// Reading and writing QP files (lib/qp/problem_io.h, membrane_generator.h):
//  - a generated membrane QP written as PROBLEM.json + .mtx + .txt and read
//    back gives the same matrix, rhs and bounds (bitwise: shortest
//    round-trip formatting);
//  - the 5-point Hessian of the thesis variant has the closed-form
//    diagonal/off-diagonal entries and ||b|| = 0.2499 at n = 2500;
//  - symmetric Matrix Market files are mirrored, duplicates summed;
//  - malformed files are rejected with a message naming the file and the
//    field or line; a non-symmetric Hessian (a lower triangle under a
//    `general' header), an entry count larger than the file can hold and a
//    cone count whose unknowns overflow 32 bits are errors (issue 15).
#include "planted_problems.h"

#include <qp/membrane_generator.h>
#include <qp/problem_io.h>
#include <util/available_memory.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <unistd.h>

using namespace dualcontact::qp;

using qptest::check;

namespace
{
  void
  write(const std::string &file, const std::string &text)
  {
    std::ofstream out(file);
    out << text;
  }

  /// read_problem(file) must throw with every piece of @p expected in the
  /// message
  void
  expect_error(const std::string              &file,
               const std::vector<std::string> &expected,
               const std::string              &what)
  {
    try
    {
      read_problem(file);
      check(false, what + " (no error)");
    }
    catch (const std::exception &e)
    {
      const std::string message = plain_message(e);
      bool              ok      = true;
      for (const auto &piece : expected)
        ok = ok && message.find(piece) != std::string::npos;
      check(ok, what);
      if (!ok)
        std::cout << "     message was: " << message << std::endl;
    }
  }
} // namespace

int
main()
{
  const std::string dir =
    (std::filesystem::temp_directory_path() /
     ("dualcontact_qpio_test_" + std::to_string(getpid())))
      .string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);

  // membrane, thesis variant, h = 50
  MembraneGenerator::Parameters prm;
  prm.h        = 50;
  auto problem = MembraneGenerator(prm).generate();
  check(problem->size() == 2500, "membrane n = 2500");
  check(std::abs(problem->rhs.l2_norm() - 0.2499) < 1e-4,
        "membrane ||b|| = 0.2499 (thesis 0.2498)");
  check(problem->hessian.el(0, 0) == 4. && problem->hessian.el(0, 1) == -1. &&
          problem->hessian.el(0, 50) == -1. && problem->hessian.el(0, 2) == 0.,
        "5-point stencil entries");
  check(problem->constraints.size() == 1 &&
          problem->constraints[0].lower[0] == -0.1 &&
          problem->constraints[0].lower[49] == -1.,
        "obstacle steps at x1 = 0.5");

  const std::string json = write_problem(*problem, dir, "membrane");
  auto              back = read_problem(json);
  bool              same =
    back->size() == problem->size() &&
    back->hessian.n_nonzero_elements() == problem->hessian.n_nonzero_elements();
  for (unsigned int r = 0; same && r < problem->size(); ++r)
    for (auto it = problem->hessian.begin(r); it != problem->hessian.end(r);
         ++it)
      same = same && back->hessian.el(r, it->column()) == it->value();
  for (unsigned int i = 0; same && i < problem->size(); ++i)
    same = same && back->rhs[i] == problem->rhs[i] &&
           back->constraints[0].lower[i] == problem->constraints[0].lower[i];
  check(same, "write_problem/read_problem round trip is exact");

  // permon variant: n = h(h+1), symmetric, row sums zero except near x1 = 0
  MembraneGenerator::Parameters permon;
  permon.variant    = MembraneGenerator::Variant::permon;
  permon.h          = 4;
  permon.load_scale = 1.;
  auto   p2         = MembraneGenerator(permon).generate();
  double max_asym = 0., sum_b = 0.;
  for (unsigned int r = 0; r < p2->size(); ++r)
    for (auto it = p2->hessian.begin(r); it != p2->hessian.end(r); ++it)
      max_asym =
        std::max(max_asym,
                 std::abs(it->value() - p2->hessian.el(it->column(), r)));
  for (unsigned int i = 0; i < p2->size(); ++i)
    sum_b += p2->rhs[i];
  check(p2->size() == 20 && max_asym == 0.,
        "permon variant: n = 20, symmetric");
  // load = -H^2 times the area of the free part (the clamped column's
  // half cells excluded): -(1 - H/2)
  check(std::abs(sum_b + (1. - 0.125)) < 1e-14,
        "permon variant: total load -(1 - H/2)");

  // a hand-written symmetric file with a duplicate and an upper entry
  write(dir + "/s.mtx",
        "%%MatrixMarket matrix coordinate real symmetric\n% comment\n"
        "3 3 5\n1 1 2\n2 1 -1\n2 2 2\n3 3 1\n3 3 1\n");
  write(dir + "/b.txt", "1\n# comment\n\n2\n3\n");
  write(dir + "/ok.json",
        R"({"hessian": "s.mtx", "rhs": "b.txt",
            "constraints": [{"type": "box", "first": 0, "count": 2,
                             "lower": -1, "upper": 1},
                            {"type": "bound", "first": 2, "count": 1,
                             "lower": 0}]})");
  auto small = read_problem(dir + "/ok.json");
  check(small->hessian.el(0, 1) == -1. && small->hessian.el(1, 0) == -1. &&
          small->hessian.el(2, 2) == 2. && small->rhs[2] == 3.,
        "symmetric file mirrored, duplicate summed, comments skipped");
  check(small->constraints.size() == 2 &&
          small->constraints[0].upper.size() == 2,
        "constraint blocks parsed");

  // bad inputs: each message must name the file and the field or line
  write(dir + "/bad1.json", R"({"hessian": "s.mtx"})");
  expect_error(dir + "/bad1.json",
               {"bad1.json", "'rhs'", "missing"},
               "missing rhs");
  write(dir + "/bad2.json", R"({"hessian": "nope.mtx", "rhs": "b.txt"})");
  expect_error(dir + "/bad2.json",
               {"bad2.json", "'hessian'", "nope.mtx"},
               "missing matrix file");
  write(dir + "/short.txt", "1\n2\n");
  write(dir + "/bad3.json", R"({"hessian": "s.mtx", "rhs": "short.txt"})");
  expect_error(dir + "/bad3.json",
               {"short.txt", "rhs", "2 values", "3"},
               "rhs of the wrong length");
  write(dir + "/bad4.json",
        R"({"hessian": "s.mtx", "rhs": "b.txt",
            "constraints": [{"type": "disc", "first": 2, "count": 1,
                             "radius": 1}]})");
  expect_error(dir + "/bad4.json",
               {"bad4.json", "constraints[0]", "exceed"},
               "block outside the problem");
  write(dir + "/bad5.json",
        R"({"hessian": "s.mtx", "rhs": "b.txt",
            "constraints": [{"type": "sphere", "first": 0, "count": 1}]})");
  expect_error(dir + "/bad5.json",
               {"constraints[0].type", "sphere"},
               "unknown block type");
  write(dir + "/bad6.json",
        R"({"hessian": "s.mtx", "rhs": "b.txt", "rsh": 1})");
  expect_error(dir + "/bad6.json", {"'rsh'", "unknown key"}, "unknown key");
  write(dir + "/broken.mtx",
        "%%MatrixMarket matrix coordinate real general\n3 3 2\n1 1 2\n4 1 x\n");
  write(dir + "/bad7.json", R"({"hessian": "broken.mtx", "rhs": "b.txt"})");
  expect_error(dir + "/bad7.json",
               {"broken.mtx:4", "index"},
               "bad matrix entry reported with its line");
  write(dir + "/bad8.json",
        R"({"hessian": "s.mtx", "rhs": "b.txt",
            "constraints": [{"type": "box", "first": 0, "count": 1,
                             "lower": 2, "upper": 1},
                            {"type": "bound", "first": 0, "count": 1,
                             "lower": 0}]})");
  expect_error(dir + "/bad8.json",
               {"constraints[0]", "lower > upper"},
               "lower > upper");
  write(dir + "/bad9.json", R"({"hessian": "s.mtx", "rhs": )");
  expect_error(dir + "/bad9.json",
               {"bad9.json", "not valid JSON"},
               "invalid JSON");
  write(dir + "/bad10.json",
        R"({"hessian": "s.mtx", "rhs": "b.txt",
            "constraints": [{"type": "bound", "first": 0, "count": 2,
                             "lower": 0},
                            {"type": "bound", "first": 1, "count": 1,
                             "lower": 0}]})");
  expect_error(dir + "/bad10.json",
               {"constraints[1]", "already constrained"},
               "overlapping blocks");

  // issue 15: a lower triangle under a `general' header is not the
  // symmetric matrix (it was read as the whole matrix and solved to a wrong
  // x reported as converged)
  write(dir + "/lower.mtx",
        "%%MatrixMarket matrix coordinate real general\n"
        "3 3 4\n1 1 2\n2 1 -1\n2 2 2\n3 3 1\n");
  write(dir + "/bad11.json", R"({"hessian": "lower.mtx", "rhs": "b.txt"})");
  expect_error(dir + "/bad11.json",
               {"lower.mtx",
                "not symmetric",
                "A(2, 1) = -1 but A(1, 2) = 0",
                "'symmetric' in its header"},
               "lower triangle under a general header");
  // a size line claiming 1e15 entries is refused before reserving memory
  write(dir + "/claim.mtx",
        "%%MatrixMarket matrix coordinate real general\n"
        "3 3 1000000000000000\n1 1 2\n");
  write(dir + "/bad12.json", R"({"hessian": "claim.mtx", "rhs": "b.txt"})");
  expect_error(dir + "/bad12.json",
               {"claim.mtx",
                "announces 1000000000000000 entries",
                "hold at most"},
               "a huge entry count is checked against the file");
  // a cone count whose product with 3 wraps around in 32 bits
  write(dir + "/bad13.json",
        R"({"hessian": "s.mtx", "rhs": "b.txt",
            "constraints": [{"type": "cone", "first": 0,
                             "count": 1431655766, "mu": 0.5}]})");
  expect_error(dir + "/bad13.json",
               {"constraints[0]", "4294967298", "exceed the problem size 3"},
               "a cone count * 3 beyond 2^32 does not wrap");

  // issue 49: a directory given as the Hessian file is named as one (fopen
  // opened it and its "size" went into std::string::resize)
  std::filesystem::create_directories(dir + "/folder.mtx");
  write(dir + "/bad14.json", R"({"hessian": "folder.mtx", "rhs": "b.txt"})");
  expect_error(dir + "/bad14.json",
               {"folder.mtx", "is a directory"},
               "a directory as the Hessian file");
  // issue 49: a size line of 2147483646 rows asks for ~170 GB: refused
  // against MemAvailable before anything is allocated (it was
  // std::bad_alloc); skipped on a machine with that much memory free
  write(dir + "/rows.mtx",
        "%%MatrixMarket matrix coordinate real general\n"
        "2147483646 2147483646 1\n1 1 2\n");
  write(dir + "/bad15.json", R"({"hessian": "rows.mtx", "rhs": "b.txt"})");
  const std::uint64_t available = dualcontact::util::available_memory();
  if (available > 0 && available < 80ull * 2147483646ull)
    expect_error(dir + "/bad15.json",
                 {"rows.mtx:2",
                  "announces a 2147483646 x 2147483646 matrix",
                  "MemAvailable"},
                 "a size line beyond the memory available");
  else
    std::cout << "skipped: the size-line memory check (MemAvailable "
              << available << " bytes)" << std::endl;

  std::filesystem::remove_all(dir);
  return qptest::checker().finish("qp/qpsolve_problem_io");
}
