#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <string>

namespace dualcontact
{
  namespace io
  {
    /**
     * Where a body is put in the scene: x -> R x + t, a rotation R about the
     * origin followed by a translation t.  Meshes are generated or read in
     * their own coordinates and then placed; every function of x in the
     * parameter file (prescribed displacements, tractions, body force) is a
     * function of the placed position.
     *
     * Parameters (subsection `Placement'):
     *  - Translation [m]: dim numbers.
     *  - Rotation angle [degrees]: counter-clockwise about the axis
     *    (2D: about the z axis).
     *  - Rotation axis [-]: 3 numbers, 3D only (ignored in 2D); need not be
     *    normalized.
     */
    template <int dim>
    class Placement
    {
    public:
      /** Declare subsection `Placement' in the current subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /**
       * Read subsection `Placement' of the current subsection, whose path
       * (for messages) is @p path.
       */
      void
      parse_parameters(dealii::ParameterHandler &prm, const std::string &path);

      /** R x + t. */
      dealii::Point<dim>
      operator()(const dealii::Point<dim> &point) const;

      /** R v. */
      dealii::Tensor<1, dim>
      rotate(const dealii::Tensor<1, dim> &vector) const;

      bool
      is_identity() const;

    private:
      dealii::Tensor<2, dim> rotation_ = dealii::unit_symmetric_tensor<dim>();
      dealii::Tensor<1, dim> translation_;
    };
  } // namespace io
} // namespace dualcontact
