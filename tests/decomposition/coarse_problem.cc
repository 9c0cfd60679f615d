// decomposition::CoarseProblem, the sparse factor of TFETI's G G', against
// dense linear algebra on a G with the structure of a decomposition: a
// chain of subdomains, each with 6 rigid-body modes, every multiplier
// (column of G) touching one subdomain (a support) or two neighbours (a
// gluing row), with random values.
//  - G~ = L^{-1} P G has orthonormal rows: G~ G~' = I to 1e-13;
//  - the projector G~'G~ equals G'(G G')^{-1} G computed densely, and
//    e~ = L^{-1} P e gives G~'e~ = G'(G G')^{-1} e;
//  - G G' is stored sparse: the nonzeros of a chain's block tridiagonal;
//  - least_squares() against the dense normal equations, on all columns
//    and on a subset; a subset that leaves one subdomain's modes without a
//    column is reported (false) and gives those modes about 0;
//  - a G whose rows are dependent (a subdomain nothing touches) throws
//    the error that names the cause.

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <decomposition/coarse_problem.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>

using namespace dealii;
using namespace dualcontact;
using decomposition::CoarseProblem;

namespace
{
  constexpr unsigned int n_rigid = 6;

  void
  check(const bool condition, const std::string &what)
  {
    if (!condition)
    {
      std::cerr << "FAILED: " << what << '\n';
      std::exit(1);
    }
  }

  /** Columns of G for a chain of @p n_subdomains: 40 gluing columns
   *  between each pair of neighbours, 30 support columns on subdomain 0,
   *  none on @p untouched (if < n_subdomains). */
  CoarseProblem::Columns
  chain(const unsigned int n_subdomains,
        const unsigned int untouched,
        std::mt19937      &random)
  {
    std::uniform_real_distribution<double> value(-1., 1.);
    CoarseProblem::Columns                 columns;
    const auto                             add = [&](const unsigned int s)
    {
      for (unsigned int k = 0; k < n_rigid; ++k)
        columns.back().emplace_back(s * n_rigid + k, value(random));
    };
    for (unsigned int c = 0; c < 30; ++c)
    {
      columns.emplace_back();
      add(0);
    }
    for (unsigned int s = 0; s + 1 < n_subdomains; ++s)
      for (unsigned int c = 0; c < 40; ++c)
      {
        columns.emplace_back();
        if (s != untouched)
          add(s);
        if (s + 1 != untouched)
          add(s + 1);
      }
    return columns;
  }

  FullMatrix<double>
  dense(const CoarseProblem::Columns &columns, const unsigned int n_modes)
  {
    FullMatrix<double> G(n_modes, columns.size());
    for (unsigned int c = 0; c < columns.size(); ++c)
      for (const auto &[k, v] : columns[c])
        G(k, c) = v;
    return G;
  }

  double
  max_abs(const FullMatrix<double> &A)
  {
    double m = 0;
    for (unsigned int i = 0; i < A.m(); ++i)
      for (unsigned int j = 0; j < A.n(); ++j)
        m = std::max(m, std::abs(A(i, j)));
    return m;
  }
} // namespace


int
main()
{
  std::mt19937             random(17);
  const unsigned int       n_subdomains = 7, n_modes = n_subdomains * n_rigid;
  const auto               columns = chain(n_subdomains, n_subdomains, random);
  const unsigned int       n       = columns.size();
  const CoarseProblem      coarse(n_modes, columns);
  const FullMatrix<double> G = dense(columns, n_modes);

  // G~ by columns of the identity, and G~ G~'
  FullMatrix<double> Gt_orthonormal(n, n_modes); // G~'
  for (unsigned int k = 0; k < n_modes; ++k)
  {
    Vector<double> y(n_modes), x;
    y(k) = 1;
    coarse.orthonormalize_transpose(y);
    coarse.Tvmult(x, y);
    for (unsigned int r = 0; r < n; ++r)
      Gt_orthonormal(r, k) = x(r);
  }
  FullMatrix<double> identity(n_modes, n_modes);
  Gt_orthonormal.Tmmult(identity, Gt_orthonormal);
  for (unsigned int k = 0; k < n_modes; ++k)
    identity(k, k) -= 1;
  std::cout << "|G~ G~' - I|_max = " << max_abs(identity) << '\n';
  check(max_abs(identity) < 1e-13, "G~ has orthonormal rows");

  // the projector onto range(G') two ways
  FullMatrix<double> GGt(n_modes, n_modes), GGt_inverse(n_modes, n_modes);
  G.mTmult(GGt, G);
  GGt_inverse.invert(GGt);
  FullMatrix<double> X(n_modes, n), projector(n, n), projector_dense(n, n);
  GGt_inverse.mmult(X, G);
  G.Tmmult(projector_dense, X);
  Gt_orthonormal.mTmult(projector, Gt_orthonormal);
  projector.add(-1., projector_dense);
  std::cout << "|G~'G~ - G'(GG')^-1 G|_max = " << max_abs(projector) << '\n';
  check(max_abs(projector) < 1e-12, "the projector equals the dense one");

  // e~ = L^{-1} P e: G~'e~ = G'(G G')^{-1} e
  Vector<double> e(n_modes), e_orthonormal, a(n_modes), b(n), c(n);
  for (unsigned int k = 0; k < n_modes; ++k)
    e(k) = std::cos(1. + k);
  e_orthonormal = e;
  coarse.orthonormalize(e_orthonormal);
  coarse.orthonormalize_transpose(e_orthonormal);
  coarse.Tvmult(b, e_orthonormal);
  GGt_inverse.vmult(a, e);
  G.Tvmult(c, a);
  b -= c;
  std::cout << "|G~'e~ - G'(GG')^-1 e|_inf = " << b.linfty_norm() << '\n';
  check(b.linfty_norm() < 1e-12 * c.linfty_norm(), "e~");

  // sparse: the chain's block tridiagonal, 36 (3 n_subdomains - 2) entries
  std::cout << "nonzeros of G G': " << coarse.n_nonzeros() << '\n';
  check(coarse.n_nonzeros() == n_rigid * n_rigid * (3 * n_subdomains - 2),
        "G G' is stored sparse");

  // least squares on all columns and on a subset
  Vector<double> r(n), alpha, rhs(n_modes), alpha_dense(n_modes);
  for (unsigned int j = 0; j < n; ++j)
    r(j) = std::sin(0.3 * j);
  for (const unsigned int stride : {1u, 2u})
  {
    const auto in_A = [stride](const unsigned int j)
    { return j % stride == 0; };
    check(coarse.least_squares(in_A, r, alpha), "determined");
    FullMatrix<double> normal(n_modes, n_modes);
    rhs = 0;
    for (unsigned int j = 0; j < n; ++j)
      if (in_A(j))
        for (unsigned int k = 0; k < n_modes; ++k)
        {
          rhs(k) += G(k, j) * r(j);
          for (unsigned int l = 0; l < n_modes; ++l)
            normal(k, l) += G(k, j) * G(l, j);
        }
    normal.gauss_jordan();
    normal.vmult(alpha_dense, rhs);
    alpha -= alpha_dense;
    std::cout << "least squares, every " << stride
              << ". column: |alpha - dense| = " << alpha.linfty_norm() << " of "
              << alpha_dense.linfty_norm() << '\n';
    check(alpha.linfty_norm() < 1e-10 * alpha_dense.linfty_norm(),
          "least squares equals the dense normal equations");
  }
  {
    // the last subdomain's columns left out: its modes are not determined
    const unsigned int first_free = 30 + 40 * (n_subdomains - 2);
    const auto         in_A       = [first_free](const unsigned int j)
    { return j < first_free; };
    check(!coarse.least_squares(in_A, r, alpha), "undetermined reported");
    double free_part = 0;
    for (unsigned int k = n_modes - n_rigid; k < n_modes; ++k)
      free_part = std::max(free_part, std::abs(alpha(k)));
    std::cout << "undetermined modes: |alpha| = " << free_part << " (others "
              << alpha.linfty_norm() << ")\n";
    check(free_part < 1e-6 * alpha.linfty_norm(),
          "the undetermined modes get about 0");
  }

  // a subdomain (3) that no column touches: G has dependent rows
  bool thrown = false;
  try
  {
    const CoarseProblem singular(n_modes, chain(n_subdomains, 3, random));
  }
  catch (const std::exception &error)
  {
    thrown =
      std::string(error.what()).find("rank deficient") != std::string::npos;
    std::cout << "singular G G': error thrown\n";
  }
  check(thrown, "a singular G G' is an error naming the cause");
  std::cout << "OK\n";
  return 0;
}
