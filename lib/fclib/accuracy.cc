#include <fclib/accuracy.h>

#include <algorithm>
#include <cmath>

namespace dualcontact
{
  namespace fclib
  {
    void
    project_on_coulomb_cone(double *z, const unsigned int dim, const double mu)
    {
      double t = 0;
      for (unsigned int k = 1; k < dim; ++k)
        t += z[k] * z[k];
      t              = std::sqrt(t);
      const double n = z[0];
      if (t <= mu * n) // inside
        return;
      if (mu * t <= -n) // in the polar cone
      {
        for (unsigned int k = 0; k < dim; ++k)
          z[k] = 0;
        return;
      }
      const double a = (n + mu * t) / (1 + mu * mu);
      z[0]           = a;
      for (unsigned int k = 1; k < dim; ++k)
        z[k] = (t > 0 ? mu * a * z[k] / t : 0.);
    }


    double
    fclib_error(const LocalProblem &problem, const dealii::Vector<double> &r)
    {
      dealii::Vector<double> u;
      problem.velocity(u, r);
      return fclib_error(problem, r, u);
    }


    double
    fclib_error(const LocalProblem           &problem,
                const dealii::Vector<double> &r,
                const dealii::Vector<double> &u)
    {
      const unsigned int dim = problem.spacedim();
      double             sum = 0;
      double             z[3];
      for (unsigned int i = 0; i < problem.n_contacts(); ++i)
      {
        const unsigned int first = dim * i;
        const double       mu    = problem.mu()[i];
        double             ut    = 0;
        for (unsigned int k = 1; k < dim; ++k)
          ut += u(first + k) * u(first + k);
        ut = std::sqrt(ut);
        for (unsigned int k = 0; k < dim; ++k)
          z[k] = r(first + k) - u(first + k) - (k == 0 ? mu * ut : 0.);
        project_on_coulomb_cone(z, dim, mu);
        for (unsigned int k = 0; k < dim; ++k)
          sum += std::pow(r(first + k) - z[k], 2);
      }
      double scale =
        std::max({problem.q().l2_norm(), r.l2_norm(), u.l2_norm()});
      if (!(scale > 0))
        scale = 1;
      return std::sqrt(sum) / scale;
    }
  } // namespace fclib
} // namespace dualcontact
