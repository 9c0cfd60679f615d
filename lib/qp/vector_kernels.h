#ifndef dualcontact_qp_vector_kernels_h
#define dualcontact_qp_vector_kernels_h

#include <cstddef>

namespace dualcontact
{
  namespace qp
  {
    /**
     * The innermost loops of the QP solvers, on raw arrays of one process'
     * entries: the active-set solvers' passes over runs of lower bounds
     * x_i >= l_i (the membrane's unknowns, the contact problem's normal
     * multipliers), the dot products after a product, the cost, the
     * spectral solvers' updates, and every dot product of the library
     * (internal::dot()).
     *
     * Why a class of its own: these loops are the solvers' whole overhead
     * beside the Hessian product (doc/benchmarks/membrane.md, goals 2 and
     * 3 of the QP issue), and the build targets the x86-64 baseline (SSE2)
     * so that the binary runs anywhere.  Written with four-wide vectors
     * (eight-wide in cg_step, conjugate_direction, gradient_norms and
     * max_step, which ran faster so with AVX-512) and compiled once per
     * instruction set (baseline, x86-64-v3 = AVX2, v4 = AVX-512; the
     * loader picks the clone for the machine, as OpenBLAS does for its
     * kernels), the comparisons, selections and sums of several entries
     * run as one instruction each, where the scalar loops made a branch or
     * a dependent sum per entry.  On the membrane at n = 2500 a CG
     * iteration's vector work fell from 136% to 27% of a mat-vec
     * (benchmarks/qp_cg_iteration.cc).
     *
     * The result does not depend on the clone: every sum is kept in eight
     * lanes, lane j taking the entries i = j (mod 8) of a run (a
     * remainder of four to seven entries: lanes 0-3 take the first four,
     * the rest goes to lane 0), and vector_kernels.cc is compiled with
     * -ffp-contract=off, so that no clone fuses a multiply-add into an FMA
     * (GCC does by default for C++): the same operations in the same order
     * run on every machine.  Callers add the lanes with Lanes::total().
     * tests/qp/vector_kernels checks every kernel against scalar loops in
     * this order, bitwise.
     */
    class VectorKernels
    {
    public:
      /// How many partial sums the kernels keep.
      static constexpr unsigned int lanes = 8;

      /// Sums in eight lanes, as the kernels keep them.
      struct Lanes
      {
        double v[lanes] = {0., 0., 0., 0., 0., 0., 0., 0.};

        /// lane 0 + lane 1 + ... + lane 7, in this order
        double
        total() const
        {
          double s = v[0];
          for (unsigned int j = 1; j < lanes; ++j)
            s += v[j];
          return s;
        }
      };

      /**
       * The smallest ratio room/q over q > 0, in eight lanes, as a
       * fraction (num, den) compared by cross-multiplication: no division
       * per entry (see SeparableSet's largest feasible step).
       */
      struct RatioLanes
      {
        double num[lanes] = {1., 1., 1., 1., 1., 1., 1., 1.};
        double den[lanes] = {0., 0., 0., 0., 0., 0., 0., 0.};
      };

      /**
       * p'Ap, p'p and g'p over n entries, added to the lanes (one pass
       * over p, Ap, g: the CG step's first pass after the product).
       */
      static void
      dots(std::size_t   n,
           const double *p,
           const double *Ap,
           const double *g,
           Lanes        &pAp,
           Lanes        &pp,
           Lanes        &gp);

      /// a'b over n entries, added to the lanes (internal::dot()).
      static void
      dot(std::size_t n, const double *a, const double *b, Lanes &ab);

      /**
       * The CG step on a run of n lower bounds l: x -= alpha p, g -= alpha
       * Ap, then at the new point, with unknown i active when x_i - l_i <=
       * tol |l_i|: the free gradient's squares (inactive g_i^2), the
       * chopped gradient's (active min(g_i, 0)^2) and phi'Ap (inactive g_i
       * Ap_i) added to the lanes.
       */
      static void
      cg_step(std::size_t   n,
              double       *x,
              double       *g,
              const double *p,
              const double *Ap,
              const double *l,
              double        tol,
              double        alpha,
              Lanes        &free_sq,
              Lanes        &chopped_sq,
              Lanes        &phi_Ap);

      /**
       * cg_step() with also the reduced chopped gradient's squares (see
       * reduced_norms()) for the step length @p reduced_alpha > 0 at the
       * new point added to @p reduced_sq: MwPGP's CG step.
       */
      static void
      cg_step_reduced(std::size_t   n,
                      double       *x,
                      double       *g,
                      const double *p,
                      const double *Ap,
                      const double *l,
                      double        tol,
                      double        alpha,
                      double        reduced_alpha,
                      Lanes        &free_sq,
                      Lanes        &chopped_sq,
                      Lanes        &phi_Ap,
                      Lanes        &reduced_sq);

      /**
       * The next conjugate direction on a run of n lower bounds l: p :=
       * phi - beta p (phi_i = g_i for inactive i, 0 for active), with p'p
       * and g'p added to the lanes and the largest feasible step along -p,
       * max(x_i - l_i, 0) / p_i over p_i > 0, offered to the ratio lanes.
       */
      static void
      conjugate_direction(std::size_t   n,
                          const double *x,
                          const double *g,
                          const double *l,
                          double        tol,
                          double        beta,
                          double       *p,
                          Lanes        &pp,
                          Lanes        &gp,
                          RatioLanes   &ratio);

      /**
       * The free gradient and the norms on a run of n lower bounds l, at x
       * with the gradient g (unknown i active when x_i - l_i <= tol
       * |l_i|): phi_i = g_i for inactive i, 0 for active, written to @p phi
       * unless it is null, the squares of phi and of the chopped gradient
       * (active min(g_i, 0)) added to the lanes.
       */
      static void
      gradient_norms(std::size_t   n,
                     const double *x,
                     const double *g,
                     const double *l,
                     double        tol,
                     double       *phi,
                     Lanes        &free_sq,
                     Lanes        &chopped_sq);

      /**
       * gradient_norms() with the reduced chopped gradient (thesis 1.4.2)
       * for the step length alpha > 0: for an active unknown g_i if g_i <
       * 0, else (x_i - max(l_i, x_i - alpha g_i)) / alpha; its squares
       * added to @p reduced_sq (no phi written).
       */
      static void
      reduced_norms(std::size_t   n,
                    const double *x,
                    const double *g,
                    const double *l,
                    double        tol,
                    double        alpha,
                    Lanes        &free_sq,
                    Lanes        &chopped_sq,
                    Lanes        &reduced_sq);

      /**
       * The largest feasible step along -p on a run of n lower bounds l:
       * max(x_i - l_i, 0) / p_i over p_i > 0, offered to the ratio lanes.
       */
      static void
      max_step(std::size_t   n,
               const double *x,
               const double *p,
               const double *l,
               RatioLanes   &ratio);

      /**
       * x := x - alpha p on a run of n lower bounds l, each new value
       * below l_i or within 8 epsilon (|x_i| + |alpha p_i| + |l_i|) of it
       * set to l_i: the step length came from rounding arithmetic, and a
       * block meant to land on its bound may miss it by a few ulps.
       */
      static void
      feasible_step(std::size_t   n,
                    double       *x,
                    const double *p,
                    const double *l,
                    double        alpha);

      /**
       * x := max(x - alpha g, l) on a run of n lower bounds; with
       * @p free_only the step is along the free gradient (no step for an
       * unknown active at x, with the tolerance @p tol).
       */
      static void
      projected_step(std::size_t   n,
                     double       *x,
                     const double *g,
                     const double *l,
                     double        tol,
                     double        alpha,
                     bool          free_only);

      /// sum of y_i (g_i - b_i) over n entries, added to the lanes: twice
      /// the cost 1/2 y'Ay - b'y from the gradient g = Ay - b.
      static void
      cost(std::size_t   n,
           const double *y,
           const double *g,
           const double *b,
           Lanes        &sum);

      /// g := g - b (g held A y), then cost(): one pass.
      static void
      residual_cost(std::size_t   n,
                    const double *y,
                    const double *b,
                    double       *g,
                    Lanes        &sum);

      /// x += beta d and g += beta Ad over n entries (a step and its
      /// gradient update, one pass).
      static void
      step(std::size_t   n,
           double        beta,
           const double *d,
           const double *Ad,
           double       *x,
           double       *g);

      /**
       * The Barzilai-Borwein quantities of the last step over n entries:
       * s = x - x_prev, y = g - g_prev, s's and s'y added to the lanes;
       * with @p copy then x_prev := x, g_prev := g (one pass).
       */
      static void
      step_differences(std::size_t   n,
                       const double *x,
                       const double *g,
                       double       *x_prev,
                       double       *g_prev,
                       bool          copy,
                       Lanes        &ss,
                       Lanes        &sy);

      /**
       * APGD's extrapolation over n entries: g = Ax - b, y = (1 + beta) x
       * - beta x_old, gy = ((1 + beta) Ax - beta Ax_old) - b.
       */
      static void
      extrapolate(std::size_t   n,
                  double        beta,
                  const double *x,
                  const double *x_old,
                  const double *Ax,
                  const double *Ax_old,
                  const double *b,
                  double       *g,
                  double       *y,
                  double       *gy);

      /// The least ratio of the lanes (infinity when none was offered).
      static double
      min_ratio(const RatioLanes &ratio);

      /**
       * Which instruction set the loader chose for the kernels:
       * "x86-64-v4", "x86-64-v3" or "baseline" (for reports).
       */
      static const char *
      instruction_set();
    };
  } // namespace qp
} // namespace dualcontact

#endif
