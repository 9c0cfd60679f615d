/**
 * @file smalse_m.h
 * SMALSE-M (thesis 2.5, algorithm 8): semimonotonic augmented Lagrangians
 * for separable and equality constrained QPs.  The equality constraints
 * Bx = c (the G lambda = e of a floating body) are enforced by an outer
 * loop over their multipliers; every outer iteration solves a QP with the
 * separable constraints only, by any solver of the factory.
 *
 * Why this structure: the inner QPs keep the separable structure the fast
 * solvers need, and the adaptive precision control (inner tolerance
 * proportional to the equality residual) and the update of M (not of the
 * penalty) give a feasibility error bounded independently of the
 * conditioning of B (thesis 2.5 and the references there).
 */
#ifndef dualcontact_qp_smalse_m_h
#define dualcontact_qp_smalse_m_h

#include <deal.II/base/parameter_handler.h>

#include <qp/solver_base.h>

#include <string>

namespace dualcontact
{
  namespace qp
  {
    /// Parameters of the SMALSE-M outer loop, subsection `QP solver` /
    /// `SMALSE-M` of the .prm.
    struct SMALSEMParameters
    {
      /// penalty rho = rho_factor * lambda_max(A) (Dostal: rho ~ ||A||)
      /// 10, not the thesis' 1: measured on the dual contact problems (F
      /// scaled to norm 1, G orthonormal), 1 needed 48 outer iterations on
      /// Hertz 3D and did not converge in 100 on a 3D Coulomb block, 10 took
      /// 13 and about 20 (inputs/hertz_3d.prm, inputs/coulomb_block.prm).
      double rho_factor = 10.;
      /// initial M_0 of the inner precision control
      /// ||g^P|| <= min(M ||Bx - c||, eta)
      double m0 = 100.;
      /// eta = eta_factor * ||b||
      double eta_factor = 0.1;
      /// beta in (0, 1): M := beta M when the Lagrangian did not increase
      /// enough
      double beta = 0.2;
      /// limit on outer iterations
      unsigned int max_outer_iterations = 100;
      /// with orthonormal equality rows (EqualityConstraints::
      /// orthonormal_rows, TFETI): minimize over P A P + rho B'B with the
      /// projector P = I - B'B (Dostal's TFETI, thesis 3.1) instead of over
      /// A + rho B'B
      bool coarse_projector = true;
      /// rho = projector_penalty_factor * lambda_max(A) with the projector;
      /// 0: automatic, EqualityConstraints::projector_penalty_factor (the
      /// formulation's measured choice)
      double projector_penalty_factor = 0.;
      /// the equality residual must satisfy ||Bx - c|| <=
      /// equality_tolerance_factor * tolerance * min(||b||, max(||c||,
      /// ||B|| ||x||)) (the thesis: ||b||; see SMALSEM)
      double equality_tolerance_factor = 1.;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      /// enters `QP solver` / `SMALSE-M` itself
      void
      parse_parameters(dealii::ParameterHandler &prm);
      void
      check() const;
    };


    /**
     * SMALSE-M with an inner solver chosen by name (parameters.solver).
     *
     * Statistics: `iterations` and the counts by kind are the sums over
     * the inner solves, `n_outer` the outer iterations, `n_hessian_products`
     * counts products with A (one per product with A + rho B'B, plus one per
     * outer iteration for the Lagrangian).  Converged when the projected
     * gradient of the Lagrangian is below tolerance * ||b|| AND
     * ||Bx - c|| <= equality_tolerance_factor * tolerance *
     * min(||b||, max(||c||, ||B|| ||x||)) (||B||^2 = EqualityConstraints::
     * norm_sq).  The thesis measures the equality against ||b||; when
     * ||b|| is much larger than the equality's own size (the dual of a stiff
     * floating body, whose ||b|| holds the initial gaps of far nodes while
     * c is its weight) that accepted x = 0 as feasible; the
     * min() never makes the test looser than the thesis'; the
     * equality residual is also stored in equality_residual().  KKT:
     * stationarity is ||g^P|| of the Lagrangian gradient
     * Ax - b + B'lambda, feasibility ||x - P(x)|| + ||Bx - c||.
     *
     * The coarse projector.  When the rows of B are orthonormal (TFETI's
     * G~, EqualityConstraints::orthonormal_rows) and coarse_projector is
     * set, the outer loop works on the equivalent problem
     *   minimize 1/2 x'PAPx - x'P(b - A x0)  subject to  Bx = c, x in Omega,
     * with P = I - B'B and x0 = B'c: on the feasible set x = Px + x0, so
     * both costs differ by a constant there, and Omega is not shifted.
     * The inner Hessian P A P + rho B'B is A restricted to the kernel of
     * B beside rho on its complement (P and B'B are complementary
     * orthogonal projectors): with rho ~ lambda_max(A) its spectrum is
     * that of A on the kernel, where the penalty form A + 10 lambda_max B'B
     * has condition number about 10 times larger and its inner solves
     * take the more iterations (measured on the brick, doc/benchmarks/
     * tfeti.md).  Each product costs two products with B and two with B'
     * more (the coarse solves of TFETI), and the stopping tests and KKT
     * residuals are those of the projected Lagrangian, whose multiplier
     * differs from the original one by B(Ax - b).
     *
     * Deviation from algorithm 8, for a black-box inner solver: the inner
     * tolerance min(M_k ||Bx - c||, eta) is evaluated with the equality
     * residual of the previous outer iterate (the inner solver's stopping
     * test is a fixed tolerance); the outer loop then checks the condition
     * at the new iterate and, if it fails, continues the inner solve from
     * there with the tighter tolerance.
     */
    template <typename VectorType>
    class AugmentedLagrangian;


    template <typename VectorType>
    class SMALSEM : public SolverBase<VectorType>
    {
    public:
      SMALSEM(const SolverParameters  &parameters,
              const SMALSEMParameters &smalse_parameters = SMALSEMParameters());

      SolverStatistics
      solve(const Problem<VectorType> &problem, VectorType &x) override;

      /// ||Bx - c|| at the returned x
      double
      equality_residual() const override;
      /// the equality multipliers at the returned x
      const VectorType &
      multipliers() const;

    private:
      /// Step 1 of algorithm 8: the inner solve to min(M ||Bx - c||, eta)
      /// (at least 0.1 tolerance), continued from the new iterate with the
      /// tighter tolerance while condition (2.36) fails there (three
      /// attempts at most); updates @p norm_residual.  False when the inner
      /// solver broke down (stats.reason and message set).
      bool
      solve_inner(const Problem<VectorType>       &inner,
                  AugmentedLagrangian<VectorType> &lagrangian,
                  const double                     M,
                  const double                     eta,
                  const double                     tolerance,
                  VectorType                      &x,
                  double                          &norm_residual,
                  SolverStatistics                &stats) const;

      /// The bound on ||Bx - c|| at @p x (see the class documentation).
      double
      equality_tolerance(const Problem<VectorType> &problem,
                         const VectorType          &x,
                         const double               norm_b) const;

      /// The outer stopping test after outer iteration @p outer: records
      /// the criterion; true, with stats.reason set, when the loop ends
      /// (converged, non-finite, an iteration limit).
      bool
      outer_loop_stops(const Problem<VectorType>       &problem,
                       AugmentedLagrangian<VectorType> &lagrangian,
                       const unsigned int               outer,
                       const VectorType                &x,
                       const double                     norm_residual,
                       const double                     tolerance,
                       SolverStatistics                &stats) const;

      /// The KKT residuals of the Lagrangian at the returned x (after
      /// finish(), which computed those of the plain gradient).
      void
      report_lagrangian_kkt(const Problem<VectorType>       &problem,
                            AugmentedLagrangian<VectorType> &lagrangian,
                            const VectorType                &x,
                            SolverStatistics                &stats) const;

      SMALSEMParameters smalse_prm;
      double            last_equality_residual = 0.;
      VectorType        lambda;
    };
  } // namespace qp
} // namespace dualcontact

#endif
