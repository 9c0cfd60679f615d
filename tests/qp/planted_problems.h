/**
 * @file planted_problems.h
 * Shared helpers of the tests in tests/qp/: dense SPD matrices, random
 * separable sets, and QPs with a planted solution (x*, active blocks and
 * positive multipliers chosen first, b = A x* + sum mu_j n_j(x*)).
 * Header-only because every test is its own program.
 */
#ifndef dualcontact_tests_qp_planted_problems_h
#define dualcontact_tests_qp_planted_problems_h

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <qp/problem.h>
#include <qp/separable_set.h>
#include <qp/solver_statistics.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace qptest
{
  using dualcontact::qp::BlockType;

  /// "1.23e-05"
  inline std::string
  sci(const double v)
  {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.3g", v);
    return buf;
  }

  /// Counts failures and prints every check.
  struct Checker
  {
    unsigned int n_checks = 0, n_failed = 0;
    bool         verbose = true;
    bool
    check(const bool ok, const std::string &what)
    {
      ++n_checks;
      if (!ok)
        ++n_failed;
      if (!ok || verbose)
        std::cout << (ok ? "  ok    " : "  FAIL  ") << what << std::endl;
      return ok;
    }
    int
    finish(const std::string &name) const
    {
      std::cout << name << ": " << n_checks - n_failed << "/" << n_checks
                << " checks passed" << std::endl;
      return n_failed == 0 ? 0 : 1;
    }
  };

  /// The one Checker of a test program that checks from free functions.
  inline Checker &
  checker()
  {
    static Checker c;
    return c;
  }

  /// checker().check(ok, what)
  inline bool
  check(const bool ok, const std::string &what)
  {
    return checker().check(ok, what);
  }

  /// uniform in [a, b)
  inline double
  uniform(std::mt19937 &rng, const double a, const double b)
  {
    return std::uniform_real_distribution<double>(a, b)(rng);
  }

  /**
   * Sparse SPD matrix: a random weighted graph Laplacian (each row linked
   * to @p neighbours random other rows, weights in [0.1, 1)) plus
   * @p shift on the diagonal.
   */
  inline void
  random_sparse_spd(const unsigned int            n,
                    const unsigned int            neighbours,
                    const double                  shift,
                    std::mt19937                 &rng,
                    dealii::SparsityPattern      &sp,
                    dealii::SparseMatrix<double> &A)
  {
    std::vector<std::vector<std::pair<unsigned int, double>>> off(n);
    std::vector<double>                                       diag(n, shift);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int k = 0; k < neighbours; ++k)
      {
        const unsigned int j = (i + 1 + rng() % (n - 1)) % n;
        const double       w = uniform(rng, 0.1, 1.);
        off[i].emplace_back(j, -w);
        off[j].emplace_back(i, -w);
        diag[i] += w;
        diag[j] += w;
      }
    std::vector<unsigned int> len(n);
    for (unsigned int i = 0; i < n; ++i)
      len[i] = off[i].size() + 1;
    sp.reinit(n, n, len);
    for (unsigned int i = 0; i < n; ++i)
      for (const auto &e : off[i])
        sp.add(i, e.first);
    sp.compress();
    A.reinit(sp);
    for (unsigned int i = 0; i < n; ++i)
    {
      A.add(i, i, diag[i]);
      for (const auto &e : off[i])
        A.add(i, e.first, e.second);
    }
  }

  /// Dense symmetric matrix, row-major.
  struct Dense
  {
    unsigned int        n = 0;
    std::vector<double> a;
    void
    vmult(double *y, const double *x) const
    {
      for (unsigned int i = 0; i < n; ++i)
      {
        double s = 0.;
        for (unsigned int j = 0; j < n; ++j)
          s += a[i * n + j] * x[j];
        y[i] = s;
      }
    }
  };

  /// A = Q diag(d) Q', d log-uniform in [lmin, lmax] (d_0 = lmin,
  /// d_{n-1} = lmax); lmin = 0 gives an SPS matrix with a kernel of
  /// dimension @p kernel.
  inline Dense
  random_spd(const unsigned int n,
             const double       lmin,
             const double       lmax,
             std::mt19937      &rng,
             const unsigned int kernel = 0)
  {
    std::normal_distribution<double> normal;
    std::vector<double>              q(n * n);
    for (double &v : q)
      v = normal(rng);
    // Gram-Schmidt on the columns (twice, for orthogonality)
    for (unsigned int pass = 0; pass < 2; ++pass)
      for (unsigned int j = 0; j < n; ++j)
      {
        for (unsigned int k = 0; k < j; ++k)
        {
          double d = 0.;
          for (unsigned int i = 0; i < n; ++i)
            d += q[i * n + j] * q[i * n + k];
          for (unsigned int i = 0; i < n; ++i)
            q[i * n + j] -= d * q[i * n + k];
        }
        double nn = 0.;
        for (unsigned int i = 0; i < n; ++i)
          nn += q[i * n + j] * q[i * n + j];
        nn = std::sqrt(nn);
        for (unsigned int i = 0; i < n; ++i)
          q[i * n + j] /= nn;
      }
    std::vector<double> d(n);
    for (unsigned int j = 0; j < n; ++j)
    {
      if (j < kernel)
        d[j] = 0.;
      else
      {
        const double lo = (kernel > 0 ? lmax * 1e-2 : lmin);
        const double t =
          (n - kernel > 1) ? double(j - kernel) / (n - kernel - 1) : 1.;
        d[j] = lo * std::pow(lmax / lo, t);
      }
    }
    Dense A;
    A.n = n;
    A.a.assign(n * n, 0.);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int k = 0; k < n; ++k)
      {
        double s = 0.;
        for (unsigned int j = 0; j < n; ++j)
          s += q[i * n + j] * d[j] * q[k * n + j];
        A.a[i * n + k] = s;
      }
    return A;
  }

  /// One block of a test set, with its parameters.
  struct Block
  {
    BlockType    type;
    unsigned int first;
    double       p1 = 0., p2 = 0., p3 = 0.; // l,u / r / a,b,angle / mu
  };

  inline unsigned int
  width(const BlockType t)
  {
    switch (t)
    {
      case BlockType::bound:
      case BlockType::box:
        return 1;
      case BlockType::disc:
      case BlockType::ellipse:
        return 2;
      case BlockType::cone:
        return 3;
    }
    return 0;
  }

  template <typename VectorType>
  std::shared_ptr<dualcontact::qp::SeparableSet<VectorType>>
  make_set(const std::vector<Block> &blocks, const VectorType &layout)
  {
    auto set = std::make_shared<dualcontact::qp::SeparableSet<VectorType>>();
    for (const Block &b : blocks)
      switch (b.type)
      {
        case BlockType::bound:
          set->add_bound(b.first, b.p1);
          break;
        case BlockType::box:
          set->add_box(b.first, b.p1, b.p2);
          break;
        case BlockType::disc:
          set->add_disc(b.first, b.p1);
          break;
        case BlockType::ellipse:
          set->add_ellipse(b.first, b.p1, b.p2, b.p3);
          break;
        case BlockType::cone:
          set->add_cone(b.first, b.p1);
          break;
      }
    set->finalize(layout);
    return set;
  }

  /// Random block parameters of a type.
  inline Block
  random_block(const BlockType    t,
               const unsigned int first,
               std::mt19937      &rng,
               const double       max_axis_ratio = 10.)
  {
    std::uniform_real_distribution<double> u(0., 1.);
    Block                                  b{t, first};
    switch (t)
    {
      case BlockType::bound:
        b.p1 = 2. * u(rng) - 1.;
        break;
      case BlockType::box:
        b.p1 = -0.5 - u(rng);
        b.p2 = b.p1 + 0.2 + 2. * u(rng);
        break;
      case BlockType::disc:
        b.p1 = 0.2 + u(rng);
        break;
      case BlockType::ellipse:
        b.p1 = 0.5 + u(rng);
        b.p2 = b.p1 / std::pow(max_axis_ratio, u(rng));
        if (u(rng) < 0.5)
          std::swap(b.p1, b.p2);
        b.p3 = 6.283185307179586 * u(rng);
        break;
      case BlockType::cone:
        b.p1 = 0.1 + u(rng);
        break;
    }
    return b;
  }

  /// A QP with known solution.
  struct Planted
  {
    Dense               A;
    std::vector<Block>  blocks;
    std::vector<double> x_star, b;
    unsigned int        n_active = 0;
  };

  /**
   * Blocks of the types in @p types (cycled), @p n_blocks of them, then
   * @p n_free unconstrained unknowns; about half of the blocks active with
   * multiplier in [0.5, 1.5] (strict complementarity), the rest strictly
   * inside.  A has spectrum in [1, kappa].
   */
  inline Planted
  make_planted(const std::vector<BlockType> &types,
               const unsigned int            n_blocks,
               const unsigned int            n_free,
               const unsigned int            seed,
               const double                  kappa          = 10.,
               const double                  max_axis_ratio = 10.)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(0., 1.);
    Planted                                P;
    unsigned int                           n = 0;
    for (unsigned int k = 0; k < n_blocks; ++k)
    {
      const BlockType t = types[k % types.size()];
      P.blocks.push_back(random_block(t, n, rng, max_axis_ratio));
      n += width(t);
    }
    const unsigned int n_constrained = n;
    n += n_free;
    P.x_star.assign(n, 0.);
    std::vector<double> normal_term(n, 0.); // sum mu_j n_j
    for (const Block &blk : P.blocks)
    {
      double      *x      = &P.x_star[blk.first];
      double      *nt     = &normal_term[blk.first];
      const bool   active = u(rng) < 0.5;
      const double mu     = 0.5 + u(rng);
      P.n_active += active ? 1 : 0;
      const double th = 6.283185307179586 * u(rng);
      switch (blk.type)
      {
        case BlockType::bound:
          x[0] = active ? blk.p1 : blk.p1 + 0.1 + u(rng);
          if (active)
            nt[0] = -mu;
          break;
        case BlockType::box:
          if (active)
          {
            const bool upper = u(rng) < 0.5;
            x[0]             = upper ? blk.p2 : blk.p1;
            nt[0]            = upper ? mu : -mu;
          }
          else
            x[0] = blk.p1 + (0.1 + 0.8 * u(rng)) * (blk.p2 - blk.p1);
          break;
        case BlockType::disc:
        {
          const double r = active ? blk.p1 : blk.p1 * (0.1 + 0.8 * u(rng));
          x[0]           = r * std::cos(th);
          x[1]           = r * std::sin(th);
          if (active)
          {
            nt[0] = mu * std::cos(th);
            nt[1] = mu * std::sin(th);
          }
          break;
        }
        case BlockType::ellipse:
        {
          const double s  = active ? 1. : 0.1 + 0.8 * u(rng);
          const double y1 = s * blk.p1 * std::cos(th);
          const double y2 = s * blk.p2 * std::sin(th);
          const double c = std::cos(blk.p3), sn = std::sin(blk.p3);
          x[0] = c * y1 - sn * y2;
          x[1] = sn * y1 + c * y2;
          if (active)
          {
            double       m1 = y1 / (blk.p1 * blk.p1);
            double       m2 = y2 / (blk.p2 * blk.p2);
            const double m  = std::sqrt(m1 * m1 + m2 * m2);
            m1 /= m;
            m2 /= m;
            nt[0] = mu * (c * m1 - sn * m2);
            nt[1] = mu * (sn * m1 + c * m2);
          }
          break;
        }
        case BlockType::cone:
        {
          const double m  = blk.p1;
          const double xn = 0.2 + u(rng);
          if (!active)
          {
            const double rt = m * xn * (0.1 + 0.8 * u(rng));
            x[0]            = xn;
            x[1]            = rt * std::cos(th);
            x[2]            = rt * std::sin(th);
          }
          else if (u(rng) < 0.25)
          {
            // apex, -g in the interior of the polar cone
            // {y_n <= -mu ||y_t||}
            const double yt = u(rng);
            x[0] = x[1] = x[2] = 0.;
            nt[0]              = -(m * yt + 0.2 + u(rng));
            nt[1]              = yt * std::cos(th);
            nt[2]              = yt * std::sin(th);
          }
          else
          {
            const double rt  = m * xn;
            x[0]             = xn;
            x[1]             = rt * std::cos(th);
            x[2]             = rt * std::sin(th);
            const double inv = mu / std::sqrt(1. + m * m);
            nt[0]            = -m * inv;
            nt[1]            = std::cos(th) * inv;
            nt[2]            = std::sin(th) * inv;
          }
          break;
        }
      }
    }
    std::normal_distribution<double> normal;
    for (unsigned int i = n_constrained; i < n; ++i)
      P.x_star[i] = normal(rng);
    P.A = random_spd(n, 1., kappa, rng);
    P.b.assign(n, 0.);
    P.A.vmult(P.b.data(), P.x_star.data());
    for (unsigned int i = 0; i < n; ++i)
      P.b[i] += normal_term[i];
    return P;
  }

  /// dst (any layout) := values at the locally owned global indices
  template <typename VectorType>
  void
  fill(VectorType &dst, const std::vector<double> &values)
  {
    const dealii::IndexSet owned = dst.locally_owned_elements();
    for (auto it = owned.begin(); it != owned.end(); ++it)
      dst[*it] = values[*it];
    dst.compress(dealii::VectorOperation::insert);
  }

  /// A Problem over @p layout for a dense matrix (replicated on every
  /// rank; products gather the source vector).
  template <typename VectorType>
  dualcontact::qp::Problem<VectorType>
  make_problem(const Dense               &A,
               const std::vector<double> &b,
               const std::vector<Block>  &blocks,
               const VectorType          &layout)
  {
    dualcontact::qp::Problem<VectorType> problem;
    problem.b.reinit(layout);
    fill(problem.b, b);
    auto Ap         = std::make_shared<Dense>(A);
    problem.hessian = [Ap](VectorType &dst, const VectorType &src)
    {
      const dealii::Vector<double> full(src); // all entries everywhere
      std::vector<double>          y(Ap->n);
      Ap->vmult(y.data(), full.begin());
      const dealii::IndexSet owned = dst.locally_owned_elements();
      double                *d     = dst.begin();
      std::size_t            k     = 0;
      for (auto it = owned.begin(); it != owned.end(); ++it, ++k)
        d[k] = y[*it];
    };
    if (!blocks.empty())
      problem.constraints = make_set(blocks, layout);
    return problem;
  }

  /// ||x - ref|| over all entries (collective).
  template <typename VectorType>
  double
  distance(const VectorType &x, const std::vector<double> &ref)
  {
    const dealii::Vector<double> full(x);
    double                       s = 0.;
    for (unsigned int i = 0; i < ref.size(); ++i)
      s += (full[i] - ref[i]) * (full[i] - ref[i]);
    return std::sqrt(s);
  }

  inline double
  norm(const std::vector<double> &v)
  {
    double s = 0.;
    for (const double x : v)
      s += x * x;
    return std::sqrt(s);
  }

  /**
   * The history's time stamps and counts are consistent with the record:
   * one of each per history entry, non-decreasing, the time within
   * [0, wall_time], the counts at most the final ones, the last criterion
   * the final one (SMALSE-M, whose final criterion also weighs the
   * equality residual, passes @p last_is_final = false).
   */
  inline bool
  history_consistent(const dualcontact::qp::SolverStatistics &s,
                     const bool last_is_final = true)
  {
    const std::size_t n = s.history.size();
    if (n == 0 || s.history_time.size() != n ||
        s.history_iterations.size() != n || s.history_products.size() != n)
      return false;
    for (std::size_t k = 0; k < n; ++k)
    {
      if (s.history_time[k] < 0. || s.history_time[k] > s.wall_time ||
          s.history_iterations[k] > s.iterations ||
          s.history_products[k] > s.n_hessian_products)
        return false;
      if (k > 0 && (s.history_time[k] < s.history_time[k - 1] ||
                    s.history_iterations[k] < s.history_iterations[k - 1] ||
                    s.history_products[k] < s.history_products[k - 1]))
        return false;
    }
    return !last_is_final || s.history.back() == s.final_criterion;
  }
} // namespace qptest

#endif
