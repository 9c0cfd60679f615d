// The preconditioners of the primal method (report, section 10) on small
// matrices with hand-checkable properties:
//  - incomplete Cholesky without fill to drop (a tridiagonal matrix) is the
//    complete factorization: E E' = C (1e-13), with and without diagonal
//    compensation;
//  - on the 5-point Laplacian (fill is dropped) IC(0) reproduces C on its
//    pattern, (E E')_ij = c_ij (1e-13), and differs outside it; the
//    compensated variant preserves the row sums, E E' 1 = C 1 (1e-13), where
//    IC(0) does not;
//  - SSOR: E E' = (D/w + L)(D/w)^{-1}(D/w + L)' (1e-13), and E^{-1}, E^{-T}
//    invert E, E';
//  - diagonal: E = D^{1/2};
//  - complete Cholesky (CHOLMOD, permuted): E^{-1} C E^{-T} = I and
//    W^{-1} C = I (1e-12);
//  - Preconditioner::create rejects an unknown name and omega outside (0,2).

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <primal/complete_cholesky.h>
#include <primal/diagonal_preconditioner.h>
#include <primal/incomplete_cholesky.h>
#include <primal/ssor_preconditioner.h>

#include <test_tools.h>

#include <cmath>
#include <functional>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

struct Matrix
{
  SparsityPattern      pattern;
  SparseMatrix<double> C;
};

// Builds the symmetric matrix from entry(i, j) on the pattern given by
// nonzero(i, j).
void
build(Matrix                                          &m,
      const unsigned int                               n,
      const std::function<double(unsigned, unsigned)> &entry)
{
  DynamicSparsityPattern dsp(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      if (entry(i, j) != 0. || i == j)
        dsp.add(i, j);
  m.pattern.copy_from(dsp);
  m.C.reinit(m.pattern);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      if (entry(i, j) != 0.)
        m.C.set(i, j, entry(i, j));
}

// dense W = E E'
FullMatrix<double>
product(const primal::LowerTriangular &E)
{
  const unsigned int n = E.size();
  FullMatrix<double> W(n, n);
  Vector<double>     e(n), t(n), w(n);
  for (unsigned int j = 0; j < n; ++j)
  {
    e    = 0.;
    e(j) = 1.;
    E.Tvmult(t, e);
    E.vmult(w, t);
    for (unsigned int i = 0; i < n; ++i)
      W(i, j) = w(i);
  }
  return W;
}

double
max_abs_entry(const SparseMatrix<double> &C)
{
  double m = 0.;
  for (const auto &e : C)
    m = std::max(m, std::abs(e.value()));
  return m;
}

int
main()
{
  // tridiagonal: no fill, IC is exact
  {
    Matrix             m;
    const unsigned int n = 30;
    build(m,
          n,
          [](unsigned i, unsigned j) -> double
          {
            if (i == j)
              return 4. + std::sin(1. + i);
            if (i + 1 == j || j + 1 == i)
              return -1. - 0.5 * std::cos(1. + std::min(i, j));
            return 0.;
          });
    for (const bool compensate : {false, true})
    {
      primal::IncompleteCholesky ic(compensate);
      ic.initialize(m.C);
      const auto W   = product(ic.factor());
      double     err = 0.;
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          err = std::max(err, std::abs(W(i, j) - m.C.el(i, j)));
      check(err < 1e-13 * max_abs_entry(m.C) && ic.shift() == 0.,
            std::string("tridiagonal: ") + ic.name() + " E E' = C, max error",
            err);
    }
  }

  // 5-point Laplacian on a 6 x 6 grid: IC(0) drops fill
  {
    Matrix             m;
    const unsigned int k = 6, n = k * k;
    build(m,
          n,
          [k](unsigned i, unsigned j) -> double
          {
            if (i == j)
              return 4.;
            const unsigned xi = i % k, yi = i / k, xj = j % k, yj = j / k;
            if ((xi == xj && (yi + 1 == yj || yj + 1 == yi)) ||
                (yi == yj && (xi + 1 == xj || xj + 1 == xi)))
              return -1.;
            return 0.;
          });
    primal::IncompleteCholesky ic(false), icd(true);
    ic.initialize(m.C);
    icd.initialize(m.C);
    const auto W = product(ic.factor()), Wd = product(icd.factor());
    double     on_pattern = 0., off_pattern = 0., row_sum = 0., row_sum_ic = 0.;
    for (unsigned int i = 0; i < n; ++i)
    {
      double sum_c = 0., sum_w = 0., sum_wd = 0.;
      for (unsigned int j = 0; j < n; ++j)
      {
        const double c = m.C.el(i, j);
        if (m.pattern.exists(i, j))
          on_pattern = std::max(on_pattern, std::abs(W(i, j) - c));
        else
          off_pattern = std::max(off_pattern, std::abs(W(i, j)));
        sum_c += c;
        sum_w += W(i, j);
        sum_wd += Wd(i, j);
      }
      row_sum    = std::max(row_sum, std::abs(sum_wd - sum_c));
      row_sum_ic = std::max(row_sum_ic, std::abs(sum_w - sum_c));
    }
    check(on_pattern < 1e-13 * 4.,
          "Laplacian: P-ILL (E E')_ij = c_ij on the pattern, max error",
          on_pattern);
    check(off_pattern > 1e-3,
          "Laplacian: P-ILL has fill outside the pattern (not C), largest",
          off_pattern);
    check(row_sum < 1e-13 * 4.,
          "Laplacian: P-ILLD preserves row sums, E E' 1 = C 1, max error",
          row_sum);
    check(row_sum_ic > 1e-3,
          "Laplacian: P-ILL does not preserve row sums, max deviation",
          row_sum_ic);

    // SSOR, omega = 1.3
    const double               omega = 1.3;
    primal::SSORPreconditioner ssor(omega);
    ssor.initialize(m.C);
    const auto         Ws = product(ssor.factor());
    FullMatrix<double> M(n, n), Minv_diag(n, n), T(n, n), Wexp(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j <= i; ++j)
        M(i, j) = i == j ? m.C.el(i, i) / omega : m.C.el(i, j);
    for (unsigned int i = 0; i < n; ++i)
      Minv_diag(i, i) = omega / m.C.el(i, i);
    M.mmult(T, Minv_diag);
    T.mTmult(Wexp, M);
    double err = 0.;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        err = std::max(err, std::abs(Ws(i, j) - Wexp(i, j)));
    check(err < 1e-13 * 4. / omega * 4.,
          "Laplacian: P-SOR E E' = (D/w + L)(D/w)^{-1}(D/w + L)', max error",
          err);

    Vector<double> x(n), y(n), z(n);
    for (unsigned int i = 0; i < n; ++i)
      x(i) = std::cos(0.7 * i);
    ssor.factor().vmult(y, x);
    ssor.apply_E_inverse(z, y);
    z -= x;
    const double e1 = z.linfty_norm();
    ssor.factor().Tvmult(y, x);
    ssor.apply_E_inverse_transpose(z, y);
    z -= x;
    check(std::max(e1, z.linfty_norm()) < 1e-13,
          "P-SOR: E^{-1} E x = x and E^{-T} E' x = x, max error",
          std::max(e1, z.linfty_norm()));

    // diagonal
    primal::DiagonalPreconditioner diagonal;
    diagonal.initialize(m.C);
    diagonal.apply_E_inverse(y, x);
    double ed = 0.;
    for (unsigned int i = 0; i < n; ++i)
      ed = std::max(ed, std::abs(y(i) * 2. - x(i)));
    check(ed < 1e-15, "P-DIAG: E^{-1} x = x / sqrt(c_ii), max error", ed);

    // complete Cholesky, permuted: E^{-1} C E^{-T} = I, W^{-1} C = I
    primal::CompleteCholesky chol;
    chol.initialize(m.C);
    Vector<double> t(n), Ct(n), w(n);
    chol.apply_E_inverse_transpose(t, x);
    m.C.vmult(Ct, t);
    chol.apply_E_inverse(w, Ct);
    w -= x;
    const double ec1 = w.linfty_norm() / x.linfty_norm();
    m.C.vmult(Ct, x);
    chol.apply_inverse(w, Ct);
    w -= x;
    const double ec2 = w.linfty_norm() / x.linfty_norm();
    check(std::max(ec1, ec2) < 1e-12,
          "P-LL: E^{-1} C E^{-T} x = x and W^{-1} C x = x, max error",
          std::max(ec1, ec2));
  }

  // bad names and omega
  bool thrown = false;
  try
  {
    primal::Preconditioner::create("jacobi");
  }
  catch (const std::exception &e)
  {
    thrown = std::string(e.what()).find("Unknown preconditioner `jacobi'") !=
             std::string::npos;
  }
  check(thrown, "unknown preconditioner name rejected", thrown);
  thrown = false;
  try
  {
    primal::Preconditioner::create("ssor", 2.);
  }
  catch (const std::exception &e)
  {
    thrown = std::string(e.what()).find("omega") != std::string::npos;
  }
  check(thrown, "SSOR omega = 2 rejected", thrown);
  check(primal::Preconditioner::create("none") == nullptr,
        "`none' is no preconditioner",
        true);
  return test_tools::finish();
}
