#pragma once

#include <deal.II/base/tensor.h>

#include <contact/contact_discretization.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * Whether the friction of its contacts can hold a floating body at all:
     * the physical reading of a frictional dual whose equality constraints
     * G lambda = e (the force balance of the floating bodies) cannot be met
     * inside the friction sets, so that SMALSE-M stops at its outer limit.
     *
     * For a floating body (no Dirichlet condition) all of whose contact
     * nodes share one normal n (flat contacts on one side of the body:
     * block on a plane, also several pairs in one plane), the normal
     * multipliers push along n only, so the tangential part T of the applied
     * load (body forces and tractions) must be carried by friction alone,
     * and the normal part N = F . n (pressing the body onto its masters) by
     * the normal forces: sum lambda_N,i = N.  The friction forces are at
     * most
     *   Coulomb: sum_i mu lambda_N,i = mu N (mu the largest coefficient of
     *            the body's pairs, of either axis when orthotropic),
     *   Tresca:  sum_i g w_i = g times the contact area (the largest bound),
     * so T above that capacity, or a load that pulls the body off its
     * masters (N < 0), leaves no static equilibrium.  Bodies with curved
     * or differently oriented contacts are not judged (normal forces can
     * carry tangential load there): no finding is not a proof of
     * equilibrium.
     */
    template <int dim>
    class FrictionCapacity
    {
    public:
      /** What the check needs of a body. */
      struct Body
      {
        std::string name;
        /** Resultant of body forces and tractions [N, N/m in 2D]. */
        dealii::Tensor<1, dim> load;
        /** No Dirichlet condition: all rigid-body motions free. */
        bool floating = false;
      };

      FrictionCapacity(const ContactDiscretization<dim> &contact,
                       const std::vector<Body>          &bodies);

      /**
       * One sentence per floating body whose load exceeds what its contacts
       * can carry (empty when none is found).
       */
      const std::vector<std::string> &
      findings() const;

    private:
      /** The finding for body @p b, or an empty string. */
      std::string
      check_body(const unsigned int b) const;

      const ContactDiscretization<dim> &contact_;
      const std::vector<Body>          &bodies_;
      std::vector<std::string>          findings_;
    };
  } // namespace contact
} // namespace dualcontact
