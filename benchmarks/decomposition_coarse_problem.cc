// TFETI's coarse problem G G' (G = R'B') as the number of subdomains grows:
// the sparse factor of decomposition::CoarseProblem against a dense
// Cholesky factor (LAPACK dpotrf, what a dense coarse problem costs at
// best; the hand-written dense Cholesky that came before was slower still).
//
//   bench_decomposition_coarse_problem [K...] [--cells M] [--dense-max-order N]
//
// For each K: a cube cut into K x K x K cubic subdomains of M x M x M
// trilinear cells (M = 4 by default), every subdomain floating with its 6
// rigid-body modes about its centroid; G has the columns TFETI's rows give
// (lib/decomposition/tfeti_dual.h): a non-redundant chain of gluing rows
// per shared node and component (+1 / -1 on two copies), and one
// Dirichlet row per copy of a node on the face x = 0 (no gluing rows
// there).  Prints one line per K: subdomains, coarse order, columns of G,
// nonzeros of G G' and of its sparse factor, the set-up (assembly and
// factorization) and one application of L^{-1} P and P' L^{-T} [ms] of
// the sparse problem; the dense factor's memory [MB], its dpotrf [s] and
// one forward-backward solve [ms] (only up to --dense-max-order, default
// 12,000: 1.2 GB).

#include <deal.II/base/timer.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <decomposition/coarse_problem.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

using namespace dealii;
using namespace dualcontact;
using decomposition::CoarseProblem;

namespace
{
  constexpr unsigned int n_rigid = 6;

  /** Row d of the 3 x 6 matrix of rigid-body modes at @p x (translations,
   *  then rotations about @p centre). */
  std::array<double, n_rigid>
  modes(const std::array<double, 3> &x,
        const std::array<double, 3> &centre,
        const unsigned int           d)
  {
    const double r[3] = {x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]};
    std::array<double, n_rigid> row{};
    row[d] = 1;
    // rotation about axis a: e_a x r
    const double rotation[3][3] = {{0, -r[2], r[1]},  // (e_0 x r) components
                                   {r[2], 0, -r[0]},  // (e_1 x r)
                                   {-r[1], r[0], 0}}; // (e_2 x r)
    for (unsigned int a = 0; a < 3; ++a)
      row[3 + a] = rotation[a][d];
    return row;
  }

  CoarseProblem::Columns
  columns_of_cube(const unsigned int K, const unsigned int M)
  {
    const unsigned int     n_nodes = K * M + 1;
    const double           h       = 1. / M; // subdomains of unit size
    CoarseProblem::Columns columns;
    const auto             centre = [&](const std::array<unsigned int, 3> &s) {
      return std::array<double, 3>{{s[0] + 0.5, s[1] + 0.5, s[2] + 0.5}};
    };
    const auto index = [K](const std::array<unsigned int, 3> &s)
    { return (s[2] * K + s[1]) * K + s[0]; };
    const auto add = [&](const std::array<unsigned int, 3> &s,
                         const std::array<double, 3>       &x,
                         const unsigned int                 d,
                         const double                       sign)
    {
      const auto row = modes(x, centre(s), d);
      for (unsigned int k = 0; k < n_rigid; ++k)
        if (row[k] != 0)
          columns.back().emplace_back(index(s) * n_rigid + k, sign * row[k]);
    };
    for (unsigned int i = 0; i < n_nodes; ++i)
      for (unsigned int j = 0; j < n_nodes; ++j)
        for (unsigned int l = 0; l < n_nodes; ++l)
        {
          const unsigned int                       node[3] = {i, j, l};
          const std::array<double, 3>              x{{i * h, j * h, l * h}};
          std::vector<std::array<unsigned int, 3>> copies{{{0, 0, 0}}};
          // the subdomains of the node: one or two per direction
          for (unsigned int a = 0; a < 3; ++a)
          {
            std::vector<std::array<unsigned int, 3>> next;
            for (auto s : copies)
            {
              if (node[a] % M == 0 && node[a] > 0)
              {
                s[a] = node[a] / M - 1;
                next.push_back(s);
              }
              if (node[a] % M != 0 || node[a] < K * M)
              {
                s[a] = std::min(node[a] / M, K - 1);
                next.push_back(s);
              }
            }
            copies = next;
          }
          if (copies.size() == 1 && i > 0)
            continue;
          for (unsigned int d = 0; d < 3; ++d)
            if (i == 0) // Dirichlet: a row per copy
              for (const auto &s : copies)
              {
                columns.emplace_back();
                add(s, x, d, 1.);
              }
            else // gluing: the chain of the copies
              for (unsigned int c = 0; c + 1 < copies.size(); ++c)
              {
                columns.emplace_back();
                add(copies[c], x, d, 1.);
                add(copies[c + 1], x, d, -1.);
              }
        }
    // the entries of a column by ascending mode
    for (auto &column : columns)
      std::sort(column.begin(), column.end());
    return columns;
  }
} // namespace


int
main(int argc, char **argv)
{
  std::vector<unsigned int> sizes;
  unsigned int              M = 4, dense_max_order = 12000;
  for (int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    if (arg == "--cells" && a + 1 < argc)
      M = std::stoi(argv[++a]);
    else if (arg == "--dense-max-order" && a + 1 < argc)
      dense_max_order = std::stoi(argv[++a]);
    else if (arg.find_first_not_of("0123456789") == std::string::npos)
      sizes.push_back(std::stoi(arg));
    else
    {
      std::cerr << "usage: bench_decomposition_coarse_problem [K...] "
                   "[--cells M] [--dense-max-order N]\n";
      return 1;
    }
  }
  if (sizes.empty())
    sizes = {2, 4, 8, 12, 16};
  std::printf("%10s %8s %10s %12s %12s %10s %10s %10s %10s %10s\n",
              "subdomains",
              "order",
              "columns",
              "nnz(GG')",
              "nnz(L)",
              "setup_s",
              "apply_ms",
              "dense_MB",
              "dpotrf_s",
              "dsolve_ms");
  for (const unsigned int K : sizes)
  {
    const unsigned int     n_modes   = K * K * K * n_rigid;
    CoarseProblem::Columns columns   = columns_of_cube(K, M);
    const std::size_t      n_columns = columns.size();
    // the dense G G' before the columns move into the coarse problem
    const bool               dense = n_modes <= dense_max_order;
    LAPACKFullMatrix<double> ggt(dense ? n_modes : 0, dense ? n_modes : 0);
    if (dense)
      for (const auto &column : columns)
        for (const auto &[k, v] : column)
          for (const auto &[l, w] : column)
            ggt(k, l) += v * w;

    const CoarseProblem coarse(n_modes, std::move(columns));
    Vector<double>      x(n_modes);
    for (unsigned int k = 0; k < n_modes; ++k)
      x(k) = 1. / (1 + k);
    Timer              timer;
    const unsigned int repeat = 20;
    for (unsigned int r = 0; r < repeat; ++r)
    {
      coarse.orthonormalize(x);
      coarse.orthonormalize_transpose(x);
    }
    const double apply_ms = 1e3 * timer.wall_time() / repeat;

    double dpotrf_s = -1, solve_ms = -1;
    if (dense)
    {
      timer.restart();
      ggt.compute_cholesky_factorization();
      dpotrf_s = timer.wall_time();
      timer.restart();
      for (unsigned int r = 0; r < repeat; ++r)
        ggt.solve(x);
      solve_ms = 1e3 * timer.wall_time() / repeat;
    }
    std::printf("%10u %8u %10zu %12zu %12.4g %10.3g %10.3g %10.4g ",
                K * K * K,
                n_modes,
                n_columns,
                coarse.n_nonzeros(),
                coarse.n_factor_nonzeros(),
                coarse.setup_time(),
                apply_ms,
                8e-6 * n_modes * static_cast<double>(n_modes));
    if (dense)
      std::printf("%10.3g %10.3g\n", dpotrf_s, solve_ms);
    else
      std::printf("%10s %10s\n", "-", "-");
    std::fflush(stdout);
  }
  return 0;
}
