#include <deal.II/base/timer.h>

#include <fem/umfpack_solver.h>

namespace dualcontact
{
  namespace fem
  {
    void
    UmfpackSolver::initialize(const dealii::SparseMatrix<double> &matrix)
    {
      dealii::Timer timer;
      factorization_.initialize(matrix);
      statistics_            = Statistics();
      statistics_.setup_time = timer.wall_time();
    }


    void
    UmfpackSolver::solve(dealii::Vector<double>       &x,
                         const dealii::Vector<double> &b) const
    {
      dealii::Timer timer;
      factorization_.vmult(x, b);
      statistics_.solve_time += timer.wall_time();
      ++statistics_.n_solves;
    }


    std::string
    UmfpackSolver::name() const
    {
      return "umfpack";
    }
  } // namespace fem
} // namespace dualcontact
