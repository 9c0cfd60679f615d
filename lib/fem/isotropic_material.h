#pragma once

#include <deal.II/base/symmetric_tensor.h>

#include <string>

namespace dualcontact
{
  namespace fem
  {
    /**
     * A homogeneous isotropic linear elastic material, given by Young's
     * modulus E [Pa] and Poisson's ratio nu [-].
     *
     * In 2D the stiffness tensor is the plane-strain one: the 2x2 block of the
     * 3D tensor, which is what the Lame form lambda tr(eps) I + 2 mu eps gives
     * with the 3D Lame constants.  The out-of-plane stress
     * sigma_zz = nu (sigma_xx + sigma_yy) is available for post-processing.
     */
    class IsotropicMaterial
    {
    public:
      /**
       * @p name is used in error messages only (e.g. "Body 1, material 3").
       * Throws if E <= 0 or nu is outside (-1, 0.5): outside that range the
       * energy is not positive definite.
       */
      IsotropicMaterial(const double       youngs_modulus,
                        const double       poisson_ratio,
                        const std::string &name = "material");

      double
      youngs_modulus() const;
      double
      poisson_ratio() const;
      /** First Lame parameter lambda = E nu / ((1 + nu)(1 - 2 nu)) [Pa]. */
      double
      lame_lambda() const;
      /** Shear modulus mu = E / (2 (1 + nu)) [Pa]. */
      double
      shear_modulus() const;

      /** C with sigma = C : eps (plane strain in 2D). */
      template <int dim>
      dealii::SymmetricTensor<4, dim>
      stiffness_tensor() const;

      /** sigma = lambda tr(eps) I + 2 mu eps. */
      template <int dim>
      dealii::SymmetricTensor<2, dim>
      stress(const dealii::SymmetricTensor<2, dim> &strain) const;

      /**
       * Von Mises equivalent stress of the full 3D stress state; in 2D (plane
       * strain) sigma_zz = nu (sigma_xx + sigma_yy) is included.
       */
      template <int dim>
      double
      von_mises_stress(const dealii::SymmetricTensor<2, dim> &stress) const;

    private:
      double youngs_modulus_;
      double poisson_ratio_;
    };
  } // namespace fem
} // namespace dualcontact
