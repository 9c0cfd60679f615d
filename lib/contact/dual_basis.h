#pragma once

#include <deal.II/base/point.h>
#include <deal.II/lac/full_matrix.h>

#include <contact/face_geometry.h>

namespace dualcontact
{
  namespace contact
  {
    /**
     * The dual (biorthogonal) multiplier basis of one slave face for the
     * dual mortar method: psi_j = sum_k A_jk phi_k with the face's vertex
     * shape functions phi_k and A = D M^-1, where M_jk = int_f phi_j phi_k
     * ds and D = diag(int_f phi_j ds) (Wohlmuth's construction), so that
     * int_f psi_j phi_k ds = delta_jk int_f phi_j ds.  That makes the
     * mortar matrix D diagonal: one constraint per slave node, the dual QP
     * unchanged.  On a segment this is psi = (1 -/+ 3 xi) / 2, on a
     * triangle (3 - 4 xi - 4 eta, 4 xi - 1, 4 eta - 1), on a
     * parallelogram the tensor product of the segment's; a non-affine
     * quadrilateral gets its own A through its area element, which is why
     * A is computed per face and not tabulated.  Only the face's vertex
     * (linear / bilinear) functions: degree-1 faces.
     */
    template <int dim>
    class DualBasis
    {
    public:
      /** The basis of @p face, which must outlive this object. */
      explicit DualBasis(const FaceGeometry<dim> &face);

      /** psi_v at the reference point @p unit. */
      double
      value(const unsigned int v, const dealii::Point<dim - 1> &unit) const;

      /** The coefficients A (row v: psi_v in the phi_k). */
      const dealii::FullMatrix<double> &
      coefficients() const;

    private:
      const FaceGeometry<dim>   &face_;
      dealii::FullMatrix<double> coefficients_;
    };
  } // namespace contact
} // namespace dualcontact
