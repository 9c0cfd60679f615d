#pragma once

#include <deal.II/lac/vector.h>

#include <fclib/local_problem.h>

namespace dualcontact
{
  namespace fclib
  {
    /**
     * The accuracy measure of the frictional contact community (FCLIB,
     * Siconos):
     *
     *   ||r - P_K(r - u - mu ||u_t|| e_n)|| / max(||q||, ||r||, ||u||),
     *
     * u = W r + q, P_K the projection onto the product of the Coulomb cones
     * K_i = {||r_t|| <= mu_i r_n} (normal first), norms Euclidean over all
     * contacts.  It is zero exactly at a solution of the Coulomb problem
     * (with De Saxce's shift), so it measures what the QP criteria of the
     * fixed point or the cone relaxation do not.  The denominator is
     * replaced by 1 if it is zero.
     */
    double
    fclib_error(const LocalProblem &problem, const dealii::Vector<double> &r);

    /**
     * The same measure for a velocity @p u given (u = W r + q of another
     * problem with the cones of @p problem, e.g. a proximal one), with
     * ||q|| of @p problem in the denominator.
     */
    double
    fclib_error(const LocalProblem           &problem,
                const dealii::Vector<double> &r,
                const dealii::Vector<double> &u);

    /**
     * P_K(z) for one cone of aperture @p mu, in place: @p z has the normal
     * component first and dim - 1 tangential ones (dim = 2 or 3).
     */
    void
    project_on_coulomb_cone(double *z, const unsigned int dim, const double mu);
  } // namespace fclib
} // namespace dualcontact
