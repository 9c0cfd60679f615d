/**
 * @file membrane_generator.h
 * The membrane-on-a-stepped-obstacle QP of thesis section 3.2.1 (benchmark
 * B4 in docs/benchmarks.md), generated without any finite element code.
 *
 * Why here and not in lib/fem: the benchmark is a pure QP test of the solver
 * library (scaling of MPRGP iterations with n, cost per Hessian product), and
 * it has to run from `qpsolve` at n = 10^6.  On a uniform grid of right
 * isosceles triangles the P1 stiffness matrix is exactly the 5-point stencil
 * (diagonal edges carry zero weight), so the Hessian is assembled edge by
 * edge: weight 1 for an interior grid edge, 1/2 for an edge on a free
 * (Neumann) boundary.
 */
#ifndef dualcontact_qp_membrane_generator_h
#define dualcontact_qp_membrane_generator_h

#include <qp/problem_io.h>
#include <util/enum_names.h>

#include <memory>
#include <string>

namespace dualcontact
{
  namespace qp
  {
    /**
     * Generator of the two membrane variants of benchmark B4.
     *
     * - Variant::thesis: unit square, u = 0 on the whole boundary, h x h
     *   interior nodes (n = h^2, grid step H = 1/(h+1)), unscaled 5-point
     *   Hessian, b_i = -load_scale * H^2.  With the unit load
     *   (load_scale = 1) the clamped membrane's lowest point is -0.0737 and
     *   never reaches the -0.1 obstacle; the thesis' ||b|| = 0.2498 at
     *   n = 2500 corresponds to load_scale = 13 (||b|| = 13*50/51^2 =
     *   0.2499), which is the default, so that the obstacle is active.
     * - Variant::permon: u = 0 only on the edge x1 = 0, free elsewhere; h
     *   divisions per side (H = 1/h), nodes (h+1)^2 minus the clamped
     *   column, n = h(h+1); lumped load b_i = -load_scale * H^2 * w_i with
     *   w_i = 1, 1/2 on a free edge, 1/4 at a free corner.
     *
     * Obstacle: l_i = -0.1 if x1 <= p, else -1.
     */
    class MembraneGenerator
    {
    public:
      enum class Variant
      {
        thesis,
        permon
      };

      struct Parameters
      {
        Variant variant = Variant::thesis;
        /// interior nodes per side (thesis) or divisions per side (permon)
        unsigned int h = 50;
        /// the obstacle steps from -0.1 to -1 at x1 = p
        double p = 0.5;
        /// load density magnitude; default 13 for the thesis variant (see
        /// above), 1 for the permon variant
        double load_scale     = 13.;
        double upper_obstacle = -0.1;
        double lower_obstacle = -1.;
      };

      explicit MembraneGenerator(const Parameters &parameters);

      /// The QP: Hessian, rhs, one "bound" block over all unknowns.
      std::unique_ptr<ProblemData>
      generate() const;

      /// Number of unknowns for the current parameters.
      unsigned int
      n_unknowns() const;

      /**
       * Closed-form extreme eigenvalues of the Hessian for the thesis
       * variant (5-point stencil with Dirichlet boundary:
       * 4 - 2 cos(i pi H) - 2 cos(j pi H)); {0, 0} for the permon variant,
       * which has no closed form.
       */
      std::pair<double, double>
      exact_extreme_eigenvalues() const;

      /// The names of Variant: "thesis", "permon".
      static constexpr util::EnumNames<Variant, 2> variant_names{
        "membrane variant",
        {{"thesis", "permon"}},
      };

    private:
      Parameters parameters;
    };
  } // namespace qp
} // namespace dualcontact

#endif
