// Times the two BLAS operations the project leans on, with whatever kernels
// OpenBLAS runs (OPENBLAS_CORETYPE, or util::blas_kernel_choice()'s choice):
//  - dsymv of order N_SYMV (the Delassus product of fclib::LocalSolver;
//    207 = Hertz L3's unknowns),
//  - dgemm of order N_GEMM (the supernodal updates of the sparse Cholesky
//    factorization).
//
//   bench_util_blas_kernels [N_SYMV=207] [N_GEMM=600]
//
// Prints one line: core symv_n symv_us gemm_n gemm_GFlops (the least time of
// 5 batches of about 0.2 s each, one thread).  scripts/bench_blas_kernels
// runs it under each kernel set the CPU supports.

#include <util/blas.h>
#include <util/blas_kernels.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <random>
#include <vector>


namespace
{
  /// least seconds per call of @p f over 5 batches of about 0.2 s
  template <typename F>
  double
  least_time(const F &f)
  {
    using Clock = std::chrono::steady_clock;
    const auto seconds =
      [](const Clock::time_point a, const Clock::time_point b)
    { return std::chrono::duration<double>(b - a).count(); };
    // calls per batch from one timed call
    auto start = Clock::now();
    f();
    const double once  = std::max(seconds(start, Clock::now()), 1e-7);
    const long   calls = std::max(1L, static_cast<long>(0.2 / once));
    double       best  = 1e300;
    for (int batch = 0; batch < 5; ++batch)
    {
      start = Clock::now();
      for (long c = 0; c < calls; ++c)
        f();
      best = std::min(best, seconds(start, Clock::now()) / calls);
    }
    return best;
  }
} // namespace

int
main(int argc, char **argv)
{
  // OpenBLAS' fast kernels on CPUs it does not recognise (a no-op when
  // OPENBLAS_CORETYPE is set, as scripts/bench_blas_kernels does)
  const std::string choice = dualcontact::util::blas_kernel_choice();
  const int         n_symv = argc > 1 ? std::atoi(argv[1]) : 207;
  const int         n_gemm = argc > 2 ? std::atoi(argv[2]) : 600;
  if (n_symv < 1 || n_gemm < 1)
  {
    std::cerr << "usage: bench_util_blas_kernels [N_SYMV=207] [N_GEMM=600] "
                 "(positive orders)\n";
    return 1;
  }
  std::mt19937                           rng(1);
  std::uniform_real_distribution<double> u(-1., 1.);
  const int                              one   = 1;
  const double                           alpha = 1., beta = 0.;

  std::vector<double> A(std::size_t(n_symv) * n_symv), x(n_symv), y(n_symv);
  for (int j = 0; j < n_symv; ++j)
    for (int i = 0; i <= j; ++i)
      A[i + std::size_t(j) * n_symv] = A[j + std::size_t(i) * n_symv] = u(rng);
  for (double &v : x)
    v = u(rng);
  const double symv = least_time(
    [&]()
    {
      dsymv_("U",
             &n_symv,
             &alpha,
             A.data(),
             &n_symv,
             x.data(),
             &one,
             &beta,
             y.data(),
             &one);
    });

  std::vector<double> B(std::size_t(n_gemm) * n_gemm),
    C(std::size_t(n_gemm) * n_gemm), D(std::size_t(n_gemm) * n_gemm);
  for (double &v : B)
    v = u(rng);
  for (double &v : C)
    v = u(rng);
  const double gemm = least_time(
    [&]()
    {
      dgemm_("N",
             "N",
             &n_gemm,
             &n_gemm,
             &n_gemm,
             &alpha,
             B.data(),
             &n_gemm,
             C.data(),
             &n_gemm,
             &beta,
             D.data(),
             &n_gemm);
    });

  const std::string core = dualcontact::util::blas_core_name();
  std::cout << (core.empty() ? "not-OpenBLAS" : core) << ' ' << n_symv << ' '
            << symv * 1e6 << ' ' << n_gemm << ' '
            << 2. * n_gemm * double(n_gemm) * n_gemm / gemm * 1e-9
            << (choice.empty() ? "" : "  # " + choice) << '\n';
  return 0;
}
