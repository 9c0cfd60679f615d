#pragma once

#include <string>

namespace dualcontact
{
  namespace contact
  {
    /**
     * The friction law of a contact pair.  Slip bounds are tractions
     * [N/m^2]; the nodal bound is the slip bound times the node's contact
     * area weight.  Orthotropic laws have two bounds (or coefficients), along
     * the pair's first and second tangent directions: the admissible
     * tangential tractions form an ellipse with those semi-axes.  In 2D there
     * is one tangent and the second value is ignored.
     */
    struct FrictionLaw
    {
      enum class Type
      {
        frictionless,       ///< Signorini only
        tresca_isotropic,   ///< given slip bound g
        tresca_orthotropic, ///< given slip bounds g1, g2
        coulomb_isotropic,  ///< psi = mu lambda_N (fixed point over Tresca)
        coulomb_orthotropic ///< psi_k = mu_k lambda_N
      };

      Type type = Type::frictionless;
      /** Tresca: slip bounds [N/m^2]; Coulomb: coefficients [-]. */
      double first  = 0;
      double second = 0;

      bool
      has_friction() const
      {
        return type != Type::frictionless;
      }
      bool
      is_coulomb() const
      {
        return type == Type::coulomb_isotropic ||
               type == Type::coulomb_orthotropic;
      }
      bool
      is_orthotropic() const
      {
        return type == Type::tresca_orthotropic ||
               type == Type::coulomb_orthotropic;
      }
    };
  } // namespace contact
} // namespace dualcontact
