#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>
#include <deal.II/physics/transformations.h>

#include <io/parameter_file.h>
#include <io/placement.h>

#include <cmath>

namespace dualcontact
{
  namespace io
  {
    template <int dim>
    void
    Placement<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Placement");
      prm.declare_entry("Translation",
                        dim == 2 ? "0, 0" : "0, 0, 0",
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               dim,
                                               dim),
                        "Translation t [m] of the body (dim numbers), "
                        "applied after the rotation: x -> R x + t.");
      prm.declare_entry("Rotation angle",
                        "0",
                        dealii::Patterns::Double(),
                        "Rotation angle [degrees] about the rotation axis "
                        "through the origin, counter-clockwise (2D: about "
                        "the z axis); within [-360, 360].");
      prm.declare_entry("Rotation axis",
                        "0, 0, 1",
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               3,
                                               3),
                        "Rotation axis [-] (3 numbers, need not be "
                        "normalized; 3D only, ignored in 2D).");
      prm.leave_subsection();
    }


    template <int dim>
    void
    Placement<dim>::parse_parameters(dealii::ParameterHandler &prm,
                                     const std::string        &parent_path)
    {
      const std::string path = join_path(parent_path, "Placement");
      prm.enter_subsection("Placement");
      const std::vector<double> translation =
        dealii::Utilities::string_to_double(
          dealii::Utilities::split_string_list(prm.get("Translation")));
      for (unsigned int d = 0; d < dim; ++d)
        translation_[d] = translation[d];

      const double degrees = prm.get_double("Rotation angle");
      // also keeps angle * pi from overflowing (1e308 degrees gave NaN)
      AssertThrow(std::abs(degrees) <= 360.,
                  dealii::ExcMessage(
                    "The rotation angle " + prm.get("Rotation angle") + " " +
                    parameter_location(path, "Rotation angle") +
                    " is outside [-360, 360] degrees."));
      const double angle = degrees * dealii::numbers::PI / 180.;
      if constexpr (dim == 2)
        rotation_ =
          dealii::Physics::Transformations::Rotations::rotation_matrix_2d(
            angle);
      else
      {
        const std::vector<double> axis = dealii::Utilities::string_to_double(
          dealii::Utilities::split_string_list(prm.get("Rotation axis")));
        dealii::Tensor<1, 3> direction({axis[0], axis[1], axis[2]});
        if (angle != 0.)
        {
          AssertThrow(direction.norm() > 0,
                      dealii::ExcMessage(
                        "The rotation axis must not be zero " +
                        parameter_location(path, "Rotation axis") + "."));
          rotation_ =
            dealii::Physics::Transformations::Rotations::rotation_matrix_3d(
              dealii::Point<3>(direction / direction.norm()), angle);
        }
      }
      prm.leave_subsection();
    }


    template <int dim>
    dealii::Point<dim>
    Placement<dim>::operator()(const dealii::Point<dim> &point) const
    {
      return dealii::Point<dim>(rotation_ * point + translation_);
    }


    template <int dim>
    dealii::Tensor<1, dim>
    Placement<dim>::rotate(const dealii::Tensor<1, dim> &vector) const
    {
      return rotation_ * vector;
    }


    template <int dim>
    bool
    Placement<dim>::is_identity() const
    {
      return (rotation_ -
              dealii::Tensor<2, dim>(dealii::unit_symmetric_tensor<dim>()))
                 .norm() == 0. &&
             translation_.norm() == 0.;
    }


    template class Placement<2>;
    template class Placement<3>;
  } // namespace io
} // namespace dualcontact
