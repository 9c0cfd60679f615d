#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/point.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <string>

namespace dualcontact
{
  namespace io
  {
    /**
     * A function given by an expression of a parameter file, whose every
     * value is checked where it is used: a value that is not finite (an
     * expression such as `1/0', `sqrt(-1)' or `1e308*10' that muparser
     * evaluates to inf or NaN at some point) throws an ExcMessage naming the
     * expression, the parameter (its subsection and entry) and the point.
     *
     * Checking once when the expression is read cannot do this: the value
     * depends on the point (`1/x' is finite away from x = 0), and only the
     * points where the scene uses the function (quadrature points of a
     * load, boundary nodes of a Dirichlet condition, the points the contact
     * search projects onto an obstacle) matter.  Without the check a
     * non-finite value travels on and surfaces far away, e.g. as a
     * rank-deficient rigid-body matrix.
     *
     * parse_function() returns its functions wrapped in this class; the
     * height of a graph obstacle is wrapped by driver::ObstacleParameters.
     */
    template <int dim>
    class CheckedFunction : public dealii::Function<dim>
    {
    public:
      /**
       * Wrap @p function, given by the text @p expression of the parameter
       * at @p parameter_location ("(`set Traction' in `subsection Body
       * 1/Traction 1')").
       */
      CheckedFunction(std::shared_ptr<dealii::Function<dim>> function,
                      const std::string                     &expression,
                      const std::string &parameter_location);

      double
      value(const dealii::Point<dim> &point,
            const unsigned int        component = 0) const override;

      void
      vector_value(const dealii::Point<dim> &point,
                   dealii::Vector<double>   &values) const override;

      /**
       * Set the time of this function and of the wrapped one: an expression
       * in the time t of a load step is evaluated by the wrapped function,
       * which must see the step's time (without this it stayed at t = 0).
       */
      void
      set_time(const double new_time) override;

    private:
      [[noreturn]] void
      throw_non_finite(const dealii::Point<dim>     &point,
                       const dealii::Vector<double> &values) const;

      std::shared_ptr<dealii::Function<dim>> function_;
      std::string                            expression_;
      std::string                            parameter_location_;
    };
  } // namespace io
} // namespace dualcontact
