#pragma once

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <contact/multiplier_distribution.h>

#include <string>

namespace dualcontact
{
  namespace contact
  {
    /**
     * The Hessian F = B K^# B' of the undecomposed dual, applied to the
     * multipliers.  Two forms (DualProblemParameters::Operator):
     *  - AssembledDualOperator: the dense m x m matrix from the bodies'
     *    Schur factors, one dsymv a product;
     *  - ImplicitDualOperator: B', one K^# solve per body, B.
     * Each on replicated vectors (every multiplier on every process) and
     * on distributed ones (each process the rows MultiplierDistribution
     * gives it).
     */
    template <int dim>
    class DualOperator
    {
    public:
      using VectorType        = dealii::Vector<double>;
      using DistributedVector = dealii::TrilinosWrappers::MPI::Vector;

      virtual ~DualOperator() = default;

      /** dst = F src on all multipliers. */
      virtual void
      vmult(VectorType &dst, const VectorType &src) const = 0;

      /**
       * dst = F src on distributed multipliers: @p dst gets the rows
       * @p owners gives this process (@p dst initialized by the caller).
       * Collective.
       */
      virtual void
      vmult(DistributedVector            &dst,
            const DistributedVector      &src,
            const MultiplierDistribution &owners) const = 0;

      /** Whether F is held as a dense matrix. */
      virtual bool
      is_assembled() const = 0;

      /** One line on the form of F and why it was chosen. */
      virtual const std::string &
      description() const = 0;

      /** Wall time [s] of assembling F (0 if implicit). */
      virtual double
      assembly_time() const = 0;
    };
  } // namespace contact
} // namespace dualcontact
