#include <deal.II/base/exceptions.h>

#include <contact/rigid_obstacle.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    PlaneObstacle<dim>::PlaneObstacle(const Point<dim>     &point,
                                      const Tensor<1, dim> &outward_normal)
        : point_(point)
        , normal_(outward_normal)
    {
      // scaled by the largest component first, so that the norm of a
      // normal such as (1e308, 1e308) does not overflow
      double largest = 0;
      for (unsigned int d = 0; d < dim; ++d)
        largest = std::max(largest, std::abs(outward_normal[d]));
      AssertThrow(largest > 0 && std::isfinite(largest),
                  ExcMessage("A plane obstacle needs a nonzero finite "
                             "normal."));
      normal_ /= largest;
      normal_ /= normal_.norm();
    }


    template <int dim>
    void
    PlaneObstacle<dim>::project(const Point<dim> &x,
                                Point<dim>       &closest,
                                Tensor<1, dim>   &normal) const
    {
      normal  = normal_;
      closest = x - ((x - point_) * normal_) * normal_;
    }


    template <int dim>
    std::string
    PlaneObstacle<dim>::description() const
    {
      std::ostringstream out;
      out << "plane through (" << point_ << ") with outward normal (" << normal_
          << ")";
      return out.str();
    }


    template <int dim>
    GraphObstacle<dim>::GraphObstacle(
      std::shared_ptr<const Function<dim - 1>> height,
      const std::string                       &expression,
      const double                             h_step)
        : height_(std::move(height))
        , expression_(expression)
        , h_step_(h_step)
    {
    }


    template <int dim>
    void
    GraphObstacle<dim>::project(const Point<dim> &x,
                                Point<dim>       &closest,
                                Tensor<1, dim>   &normal) const
    {
      // Minimize phi(s) = |(s, h(s)) - x|^2 / 2 over s in R^{dim-1}: Newton
      // with the Gauss-Newton Hessian I + grad h grad h', damped by halving.
      Point<dim - 1> s;
      for (unsigned int d = 0; d + 1 < dim; ++d)
        s[d] = x[d];
      const auto evaluate =
        [&](const Point<dim - 1> &s_, Tensor<1, dim - 1> &grad)
      {
        for (unsigned int d = 0; d + 1 < dim; ++d)
        {
          Point<dim - 1> plus = s_, minus = s_;
          plus[d] += h_step_;
          minus[d] -= h_step_;
          grad[d] =
            (height_->value(plus) - height_->value(minus)) / (2 * h_step_);
        }
        return height_->value(s_);
      };
      const auto distance2 = [&](const Point<dim - 1> &s_)
      {
        double value = 0;
        for (unsigned int d = 0; d + 1 < dim; ++d)
          value += (s_[d] - x[d]) * (s_[d] - x[d]);
        const double h = height_->value(s_);
        return value + (h - x[dim - 1]) * (h - x[dim - 1]);
      };
      for (unsigned int it = 0; it < 50; ++it)
      {
        Tensor<1, dim - 1> grad_h;
        const double       h = evaluate(s, grad_h);
        // gradient of phi
        Tensor<1, dim - 1> g;
        for (unsigned int d = 0; d + 1 < dim; ++d)
          g[d] = (s[d] - x[d]) + (h - x[dim - 1]) * grad_h[d];
        // a slope that overflows: stop here, the normal below says so
        if (!std::isfinite(g.norm()))
          break;
        // (I + a a') step = -g  by Sherman-Morrison
        const double       a2      = grad_h * grad_h;
        Tensor<1, dim - 1> step    = -g + ((grad_h * g) / (1 + a2)) * grad_h;
        double             current = distance2(s), tau = 1;
        Point<dim - 1>     trial = s + step;
        while (distance2(trial) > current && tau > 1e-8)
        {
          tau /= 2;
          trial = s + tau * step;
        }
        s = trial;
        if (tau * step.norm() <= 1e-14 * (1 + s.norm()))
          break;
      }
      Tensor<1, dim - 1> grad_h;
      const double       h = evaluate(s, grad_h);
      for (unsigned int d = 0; d + 1 < dim; ++d)
      {
        closest[d] = s[d];
        normal[d]  = -grad_h[d];
      }
      closest[dim - 1] = h;
      normal[dim - 1]  = 1;
      // scaled by its largest component first: a steep slope (1e200)
      // squared would overflow the norm; a slope that overflows itself
      // leaves the normal not finite, for the caller to name (see
      // driver::ObstacleParameters)
      double largest = 0;
      for (unsigned int d = 0; d < dim; ++d)
        largest = std::max(largest, std::abs(normal[d]));
      normal /= largest;
      normal /= normal.norm();
    }


    template <int dim>
    std::string
    GraphObstacle<dim>::description() const
    {
      return "region below the graph of h = " + expression_;
    }


    template class PlaneObstacle<2>;
    template class PlaneObstacle<3>;
    template class GraphObstacle<2>;
    template class GraphObstacle<3>;
  } // namespace contact
} // namespace dualcontact
