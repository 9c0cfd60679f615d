#include <deal.II/base/quadrature.h>
#include <deal.II/lac/vector.h>

#include <contact/dual_basis.h>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    DualBasis<dim>::DualBasis(const FaceGeometry<dim> &face)
        : face_(face)
    {
      const unsigned int n = face.n_vertices();
      // phi_j phi_k times the area element: degree 2 per direction on a
      // segment, triangle or parallelogram, 4 on a warped quadrilateral's
      // jacobian; 3 points per direction integrate degree 5 exactly
      const Quadrature<dim - 1> quadrature = face.reference_quadrature(3);
      FullMatrix<double>        mass(n, n);
      Vector<double>            lumped(n);
      for (unsigned int q = 0; q < quadrature.size(); ++q)
      {
        const Point<dim - 1> &x = quadrature.point(q);
        const double jxw = quadrature.weight(q) * face.jacobian_determinant(x);
        for (unsigned int j = 0; j < n; ++j)
        {
          const double phi_j = face.shape_value(j, x);
          lumped(j) += phi_j * jxw;
          for (unsigned int k = 0; k < n; ++k)
            mass(j, k) += phi_j * face.shape_value(k, x) * jxw;
        }
      }
      mass.gauss_jordan();
      coefficients_.reinit(n, n);
      for (unsigned int j = 0; j < n; ++j)
        for (unsigned int k = 0; k < n; ++k)
          coefficients_(j, k) = lumped(j) * mass(j, k);
    }


    template <int dim>
    double
    DualBasis<dim>::value(const unsigned int    v,
                          const Point<dim - 1> &unit) const
    {
      double psi = 0;
      for (unsigned int k = 0; k < coefficients_.n(); ++k)
        psi += coefficients_(v, k) * face_.shape_value(k, unit);
      return psi;
    }


    template <int dim>
    const FullMatrix<double> &
    DualBasis<dim>::coefficients() const
    {
      return coefficients_;
    }


    template class DualBasis<2>;
    template class DualBasis<3>;
  } // namespace contact
} // namespace dualcontact
