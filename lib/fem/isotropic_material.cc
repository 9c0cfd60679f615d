#include <deal.II/base/exceptions.h>

#include <fem/isotropic_material.h>

#include <cmath>

namespace dualcontact
{
  namespace fem
  {
    IsotropicMaterial::IsotropicMaterial(const double       youngs_modulus,
                                         const double       poisson_ratio,
                                         const std::string &name)
        : youngs_modulus_(youngs_modulus)
        , poisson_ratio_(poisson_ratio)
    {
      AssertThrow(std::isfinite(youngs_modulus) && youngs_modulus > 0,
                  dealii::ExcMessage(name + ": Young's modulus E must be > 0 " +
                                     "(got " + std::to_string(youngs_modulus) +
                                     ")."));
      AssertThrow(std::isfinite(poisson_ratio) && poisson_ratio > -1. &&
                    poisson_ratio < 0.5,
                  dealii::ExcMessage(name +
                                     ": Poisson's ratio nu must lie in "
                                     "(-1, 0.5) (got " +
                                     std::to_string(poisson_ratio) + ")."));
    }


    double
    IsotropicMaterial::youngs_modulus() const
    {
      return youngs_modulus_;
    }


    double
    IsotropicMaterial::poisson_ratio() const
    {
      return poisson_ratio_;
    }


    double
    IsotropicMaterial::lame_lambda() const
    {
      return youngs_modulus_ * poisson_ratio_ /
             ((1. + poisson_ratio_) * (1. - 2. * poisson_ratio_));
    }


    double
    IsotropicMaterial::shear_modulus() const
    {
      return youngs_modulus_ / (2. * (1. + poisson_ratio_));
    }


    template <int dim>
    dealii::SymmetricTensor<4, dim>
    IsotropicMaterial::stiffness_tensor() const
    {
      const double                    lambda = lame_lambda();
      const double                    mu     = shear_modulus();
      dealii::SymmetricTensor<4, dim> C;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int l = 0; l < dim; ++l)
              C[i][j][k][l] = (i == j && k == l ? lambda : 0.) +
                              ((i == k && j == l) ? mu : 0.) +
                              ((i == l && j == k) ? mu : 0.);
      return C;
    }


    template <int dim>
    dealii::SymmetricTensor<2, dim>
    IsotropicMaterial::stress(
      const dealii::SymmetricTensor<2, dim> &strain) const
    {
      return lame_lambda() * dealii::trace(strain) *
               dealii::unit_symmetric_tensor<dim>() +
             2. * shear_modulus() * strain;
    }


    template <int dim>
    double
    IsotropicMaterial::von_mises_stress(
      const dealii::SymmetricTensor<2, dim> &stress) const
    {
      // Full 3D stress: in plane strain sigma_zz = nu (sigma_xx + sigma_yy).
      double s[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          s[i][j] = stress[i][j];
      if (dim == 2)
        s[2][2] = poisson_ratio_ * (stress[0][0] + stress[1][1]);
      const double d01 = s[0][0] - s[1][1];
      const double d12 = s[1][1] - s[2][2];
      const double d20 = s[2][2] - s[0][0];
      return std::sqrt(
        0.5 * (d01 * d01 + d12 * d12 + d20 * d20) +
        3. * (s[0][1] * s[0][1] + s[1][2] * s[1][2] + s[2][0] * s[2][0]));
    }


    template dealii::SymmetricTensor<4, 2>
    IsotropicMaterial::stiffness_tensor<2>() const;
    template dealii::SymmetricTensor<4, 3>
    IsotropicMaterial::stiffness_tensor<3>() const;
    template dealii::SymmetricTensor<2, 2>
    IsotropicMaterial::stress<2>(const dealii::SymmetricTensor<2, 2> &) const;
    template dealii::SymmetricTensor<2, 3>
    IsotropicMaterial::stress<3>(const dealii::SymmetricTensor<2, 3> &) const;
    template double
    IsotropicMaterial::von_mises_stress<2>(
      const dealii::SymmetricTensor<2, 2> &) const;
    template double
    IsotropicMaterial::von_mises_stress<3>(
      const dealii::SymmetricTensor<2, 3> &) const;
  } // namespace fem
} // namespace dualcontact
