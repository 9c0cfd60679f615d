#include <deal.II/base/exceptions.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <driver/obstacle_parameters.h>
#include <io/checked_function.h>
#include <io/parameter_file.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dualcontact
{
  namespace driver
  {
    namespace
    {
      std::string
      zero_point(const unsigned int dim)
      {
        return dim == 2 ? "0, 0" : "0, 0, 0";
      }

      std::string
      up_vector(const unsigned int dim)
      {
        return dim == 2 ? "0, 1" : "0, 0, 1";
      }

      /**
       * A graph obstacle whose normal is checked where the contact search
       * projects: a slope that overflows (the height's central difference,
       * e.g. of 1.7e308*tanh(1e9*x)) is refused naming the parameter and
       * the point.  Its heights are checked by the io::CheckedFunction it
       * is given.
       */
      template <int dim>
      class CheckedGraphObstacle : public contact::GraphObstacle<dim>
      {
      public:
        CheckedGraphObstacle(
          std::shared_ptr<const dealii::Function<dim - 1>> height,
          const std::string                               &expression,
          const std::string                               &parameter_location)
            : contact::GraphObstacle<dim>(std::move(height), expression)
            , expression_(expression)
            , parameter_location_(parameter_location)
        {
        }

        void
        project(const dealii::Point<dim> &x,
                dealii::Point<dim>       &closest,
                dealii::Tensor<1, dim>   &normal) const override
        {
          contact::GraphObstacle<dim>::project(x, closest, normal);
          bool finite = true;
          for (unsigned int d = 0; d < dim; ++d)
            finite = finite && std::isfinite(normal[d]);
          if (finite)
            return;
          std::ostringstream message;
          message << "The height function `" << expression_ << "' "
                  << parameter_location_
                  << " has no finite slope where the contact search projects "
                     "the point (";
          for (unsigned int d = 0; d < dim; ++d)
            message << (d == 0 ? "" : ", ") << x[d];
          message << "): check it for an overflow or a jump to infinity.";
          AssertThrow(false, dealii::ExcMessage(message.str()));
        }

      private:
        std::string expression_;
        std::string parameter_location_;
      };


      template <int dim>
      dealii::Tensor<1, dim>
      parse_vector(const std::string &text)
      {
        const std::vector<double> values = dealii::Utilities::string_to_double(
          dealii::Utilities::split_string_list(text));
        dealii::Tensor<1, dim> vector;
        for (unsigned int d = 0; d < dim; ++d)
          vector[d] = values[d];
        return vector;
      }
    } // namespace


    template <int dim>
    void
    ObstacleParameters<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry(
        "Type",
        "plane",
        dealii::Patterns::Selection("plane|graph"),
        "The shape of the rigid obstacle. `plane': the half-space behind the "
        "plane through `Point' with outward normal `Outward normal' (the "
        "bodies are on the side the normal points to). `graph': the region "
        "below the graph of `Height function', y <= h(x) in 2D, z <= h(x, y) "
        "in 3D (the last coordinate points up).");
      prm.declare_entry("Point",
                        zero_point(dim),
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               dim,
                                               dim),
                        "plane: a point of the plane [m] (dim numbers, "
                        "placed coordinates).");
      prm.declare_entry("Outward normal",
                        up_vector(dim),
                        dealii::Patterns::List(dealii::Patterns::Double(),
                                               dim,
                                               dim),
                        "plane: the normal pointing out of the obstacle, "
                        "towards the bodies [-] (dim numbers, need not be "
                        "normalized, not zero).");
      prm.declare_entry("Height function",
                        "0",
                        dealii::Patterns::Anything(),
                        "graph: the height h [m] of the obstacle's surface "
                        "as a function of x (2D) or of x, y (3D) [m] "
                        "(muparser syntax; the constant pi is known). The "
                        "obstacle is the region below it.");
    }


    template <int dim>
    void
    ObstacleParameters<dim>::parse_parameters(dealii::ParameterHandler &prm,
                                              const std::string        &path)
    {
      name = path;
      if (prm.get("Type") == "plane")
      {
        const dealii::Tensor<1, dim> point_vector =
          parse_vector<dim>(prm.get("Point"));
        dealii::Tensor<1, dim> normal =
          parse_vector<dim>(prm.get("Outward normal"));
        // scaled by its largest component before it is normalized: the
        // norm of (1e308, 1e308) overflows, that of (0, 1e-300) underflows
        double largest = 0;
        for (unsigned int d = 0; d < dim; ++d)
          largest = std::max(largest, std::abs(normal[d]));
        AssertThrow(largest > 0,
                    dealii::ExcMessage(
                      "The outward normal of " + path + " is zero " +
                      io::parameter_location(path, "Outward normal") +
                      ": give the direction from the obstacle towards the "
                      "bodies."));
        normal /= largest;
        normal /= normal.norm();
        obstacle = std::make_shared<contact::PlaneObstacle<dim>>(
          dealii::Point<dim>(point_vector), normal);
      }
      else
      {
        const std::string expression = prm.get("Height function");
        const std::string variables  = dim == 2 ? "x" : "x,y";
        auto height = std::make_shared<dealii::FunctionParser<dim - 1>>(1);
        try
        {
          height->initialize(variables,
                             expression,
                             {{"pi", dealii::numbers::PI}});
          // muparser compiles lazily: evaluate once to find errors now
          height->value(dealii::Point<dim - 1>());
        }
        catch (const dealii::ExceptionBase &exception)
        {
          std::ostringstream info;
          exception.print_info(info);
          AssertThrow(false,
                      dealii::ExcMessage(
                        "Cannot parse the height function `" + expression +
                        "' " + io::parameter_location(path, "Height function") +
                        " (variables: " + variables + "; constant: pi): " +
                        dealii::Utilities::trim(info.str())));
        }
        // the heights the contact search evaluates are checked to be
        // finite, naming the entry and the point
        const std::string location =
          io::parameter_location(path, "Height function");
        obstacle = std::make_shared<CheckedGraphObstacle<dim>>(
          std::make_shared<io::CheckedFunction<dim - 1>>(height,
                                                         expression,
                                                         location),
          expression,
          location);
      }
    }


    template class ObstacleParameters<2>;
    template class ObstacleParameters<3>;
  } // namespace driver
} // namespace dualcontact
