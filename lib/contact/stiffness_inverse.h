#pragma once

#include <deal.II/lac/vector.h>

#include <contact/contact_discretization.h>
#include <fem/elastic_body.h>
#include <fem/stiffness_solver.h>

#include <memory>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * K^# = diag(K_b^#) of the bodies in the stacked dof numbering of
     * ContactDiscretization: K_b^{-1} for a supported body, the fixing-dof
     * generalized inverse for a body with rigid-body modes (the solvers
     * come factorized, one per body in order).
     */
    template <int dim>
    class StiffnessInverse
    {
    public:
      StiffnessInverse(const std::vector<const fem::ElasticBody<dim> *> &bodies,
                       const ContactDiscretization<dim> &contact);

      /** The factorized solver of the next body. */
      void
      add(std::unique_ptr<fem::StiffnessSolver> solver);

      /** x := K^# x (one solve per body, counted as one). */
      void
      apply(dealii::Vector<double> &x) const;

      /** Whether a body's solver is spread over the processes (then
       *  apply() is collective). */
      bool
      is_distributed() const;

      /** Number of apply() calls so far. */
      unsigned long
      n_solves() const;
      /** Wall time [s] of the bodies' factorizations. */
      double
      setup_time() const;
      /** Wall time [s] of all solves so far (over all bodies). */
      double
      solve_time() const;

    private:
      std::vector<const fem::ElasticBody<dim> *>         bodies_;
      const ContactDiscretization<dim>                  &contact_;
      std::vector<std::unique_ptr<fem::StiffnessSolver>> solvers_;
      mutable unsigned long                              n_solves_ = 0;
    };
  } // namespace contact
} // namespace dualcontact
