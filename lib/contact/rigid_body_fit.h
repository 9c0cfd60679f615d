#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <contact/contact_discretization.h>
#include <contact/contact_rows.h>

#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * The last part of the recovery of the undecomposed dual: u = K^#(f -
     * B'lambda) is known up to a rigid-body motion R alpha of the floating
     * bodies; alpha is the least-squares solution of G_A' alpha = -r_A,
     * r = B u - [c; -o_T] (= d - F lambda) the residual of the constraints
     * without the rigid motion, over the rows A that must hold with
     * equality (chosen by the caller: DualProblem's active rows), i.e.
     * (G_A G_A') alpha = -G_A r_A.
     */
    template <int dim>
    class RigidBodyFit
    {
    public:
      /**
       * The columns of R over the stacked dofs (@p rigid_modes) and the
       * rows of G = R'B' (@p G_rows); every argument must outlive this
       * object (the vectors may be filled afterwards).
       */
      RigidBodyFit(const ContactDiscretization<dim>          &contact,
                   const ContactRows<dim>                    &rows,
                   const std::vector<unsigned int>           &frictional_nodes,
                   const std::vector<dealii::Vector<double>> &rigid_modes,
                   const std::vector<dealii::Vector<double>> &G_rows);

      /**
       * u += R alpha from the rows @p owned_rows (global indices) where
       * @p active is set, the sums G_A G_A' and G_A r_A reduced over
       * @p communicator (collective).  When no active row sees a
       * rigid-body mode (G_A G_A' = 0) the motion is not determined: with
       * @p require_determined this throws, otherwise u is left as it is
       * and false is returned.  A mode that no active row sees is left at
       * zero (regularized inverse).
       */
      bool
      add(dealii::Vector<double>          &u,
          const std::vector<unsigned int> &owned_rows,
          const std::vector<bool>         &active,
          MPI_Comm                         communicator,
          const bool                       require_determined) const;

      /**
       * The slip of the previous load step (dim - 1 values per contact
       * node; empty: none), which the tangential rows then hold to: their
       * residual is B_T u + o_T - s (@p slip must outlive this object).
       */
      void
      set_previous_slip(const dealii::Vector<double> *slip)
      {
        previous_slip_ = slip;
      }

    private:
      /** u += R alpha, (G_A G_A') alpha = rhs; @p GGt is regularized. */
      bool
      add_rigid_motion(dealii::FullMatrix<double>   &GGt,
                       const dealii::Vector<double> &rhs,
                       dealii::Vector<double>       &u,
                       const bool                    require_determined) const;

      const ContactDiscretization<dim>          &contact_;
      const ContactRows<dim>                    &rows_;
      const std::vector<unsigned int>           &frictional_nodes_;
      const std::vector<dealii::Vector<double>> &rigid_modes_;
      const std::vector<dealii::Vector<double>> &G_rows_;
      const dealii::Vector<double>              *previous_slip_ = nullptr;
    };
  } // namespace contact
} // namespace dualcontact
