#pragma once

#include <deal.II/base/function.h>

#include <memory>
#include <string>

namespace dualcontact
{
  namespace io
  {
    /**
     * A vector-valued function of the position, given in a parameter file as
     * @p n_components expressions separated by `;' (muparser syntax, as in
     * deal.II's FunctionParser), e.g. `0; -1e6*x; 0'.  The variables are x, y
     * (and z in 3D) and the time t of a load step (Function::set_time(), 0
     * until set; subsection `Load steps'); the constant pi is defined.
     *
     * Throws an ExcMessage naming @p parameter_location if the number of
     * expressions is wrong or an expression does not parse or evaluate.
     * The function returned is a CheckedFunction: a value that is not
     * finite where it is evaluated throws, naming the parameter and the
     * point.
     */
    template <int dim>
    std::shared_ptr<dealii::Function<dim>>
    parse_function(const std::string &expressions,
                   const unsigned int n_components,
                   const std::string &parameter_location);

    /** The default text of a function with @p n_components zeros: "0; 0". */
    std::string
    zero_expressions(const unsigned int n_components);
  } // namespace io
} // namespace dualcontact
