#pragma once

#include <contact/contact_rows.h>
#include <contact/dual_operator.h>
#include <contact/stiffness_inverse.h>

#include <string>

namespace dualcontact
{
  namespace contact
  {
    /**
     * F = B K^# B' applied as it stands: B' lambda, one solve with every
     * body's whole factor, B.  Distributed: each process applies B' to its
     * owned multipliers, the partial loads are summed (one MPI_Allreduce
     * of the n dofs of all bodies), K^# is applied by the stiffness
     * solvers, and each process applies its rows of B.
     */
    template <int dim>
    class ImplicitDualOperator : public DualOperator<dim>
    {
    public:
      using typename DualOperator<dim>::VectorType;
      using typename DualOperator<dim>::DistributedVector;

      /** @p rows and @p inverse must outlive this object; @p description:
       *  "implicit (why)". */
      ImplicitDualOperator(const ContactRows<dim>      &rows,
                           const StiffnessInverse<dim> &inverse,
                           const std::string           &description);

      void
      vmult(VectorType &dst, const VectorType &src) const override;
      void
      vmult(DistributedVector            &dst,
            const DistributedVector      &src,
            const MultiplierDistribution &owners) const override;
      bool
      is_assembled() const override;
      const std::string &
      description() const override;
      double
      assembly_time() const override;

    private:
      const ContactRows<dim>      &rows_;
      const StiffnessInverse<dim> &inverse_;
      const std::string            description_;
    };
  } // namespace contact
} // namespace dualcontact
