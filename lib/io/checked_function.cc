#include <deal.II/base/exceptions.h>

#include <io/checked_function.h>
#include <io/parameter_file.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace dualcontact
{
  namespace io
  {
    template <int dim>
    CheckedFunction<dim>::CheckedFunction(
      std::shared_ptr<dealii::Function<dim>> function,
      const std::string                     &expression,
      const std::string                     &parameter_location)
        : dealii::Function<dim>(function->n_components)
        , function_(std::move(function))
        , expression_(expression)
        , parameter_location_(parameter_location)
    {
    }


    template <int dim>
    void
    CheckedFunction<dim>::set_time(const double new_time)
    {
      dealii::Function<dim>::set_time(new_time);
      function_->set_time(new_time);
    }


    template <int dim>
    double
    CheckedFunction<dim>::value(const dealii::Point<dim> &point,
                                const unsigned int        component) const
    {
      const double result = function_->value(point, component);
      if (!std::isfinite(result))
      {
        dealii::Vector<double> values(this->n_components);
        function_->vector_value(point, values);
        values(component) = result;
        throw_non_finite(point, values);
      }
      return result;
    }


    template <int dim>
    void
    CheckedFunction<dim>::vector_value(const dealii::Point<dim> &point,
                                       dealii::Vector<double>   &values) const
    {
      function_->vector_value(point, values);
      for (const double v : values)
        if (!std::isfinite(v))
          throw_non_finite(point, values);
    }


    template <int dim>
    void
    CheckedFunction<dim>::throw_non_finite(
      const dealii::Point<dim>     &point,
      const dealii::Vector<double> &values) const
    {
      std::ostringstream message;
      message.precision(6);
      message << "The expression `" << shorten_for_message(expression_) << "' "
              << parameter_location_ << " is not finite at the point (";
      for (unsigned int d = 0; d < dim; ++d)
        message << (d == 0 ? "" : ", ") << point[d];
      message << "), where it is (";
      for (unsigned int c = 0; c < values.size(); ++c)
        message << (c == 0 ? "" : ", ") << values[c];
      message << "): check it for a division by zero, the square root or "
                 "logarithm of a negative number, an overflow.";
      AssertThrow(false, dealii::ExcMessage(message.str()));
      std::abort(); // not reached
    }


    template class CheckedFunction<1>;
    template class CheckedFunction<2>;
    template class CheckedFunction<3>;
  } // namespace io
} // namespace dualcontact
