#pragma once

#include <deal.II/lac/sparse_direct.h>

#include <fem/stiffness_solver.h>

namespace dualcontact
{
  namespace fem
  {
    /**
     * Sparse LU by UMFPACK through deal.II's SparseDirectUMFPACK.  Kept as an
     * independent check of CHOLMOD and for small 2D scenes; in 3D it is
     * far slower than CholmodSolver (190 s against 7 s on 92k dofs).
     */
    class UmfpackSolver : public StiffnessSolver
    {
    public:
      void
      initialize(const dealii::SparseMatrix<double> &matrix) override;

      void
      solve(dealii::Vector<double>       &x,
            const dealii::Vector<double> &b) const override;

      std::string
      name() const override;

    private:
      dealii::SparseDirectUMFPACK factorization_;
    };
  } // namespace fem
} // namespace dualcontact
