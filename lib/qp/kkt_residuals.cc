#include <qp/kkt_residuals.h>
#include <qp/vector_helpers.h>

#include <deal.II/base/exceptions.h>

namespace dualcontact
{
  namespace qp
  {
    template <typename VectorType>
    KKTResiduals
    compute_kkt_residuals(const Problem<VectorType> &problem,
                          const VectorType          &x)
    {
      KKTResiduals r;
      VectorType   xp(x), g(x);
      if (problem.constraints)
      {
        r.feasibility = problem.constraints->feasibility_violation(x);
        problem.constraints->project(xp);
      }
      problem.hessian(g, xp);
      g -= problem.b;
      if (problem.constraints)
      {
        VectorType gp(x);
        problem.constraints->projected_gradient(xp, g, gp);
        r.stationarity    = internal::norm(gp);
        r.complementarity = problem.constraints->complementarity(xp, g);
      }
      else
        r.stationarity = internal::norm(g);
      if (problem.equality)
      {
        VectorType bx(problem.equality->c);
        problem.equality->vmult(bx, x);
        bx -= problem.equality->c;
        r.feasibility += internal::norm(bx);
      }
      return r;
    }


    template KKTResiduals
    compute_kkt_residuals<dealii::Vector<double>>(
      const Problem<dealii::Vector<double>> &,
      const dealii::Vector<double> &);
    template KKTResiduals
    compute_kkt_residuals<dealii::TrilinosWrappers::MPI::Vector>(
      const Problem<dealii::TrilinosWrappers::MPI::Vector> &,
      const dealii::TrilinosWrappers::MPI::Vector &);
  } // namespace qp
} // namespace dualcontact
