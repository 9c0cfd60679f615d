#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <memory>
#include <string>

namespace dualcontact
{
  namespace contact
  {
    /**
     * A rigid obstacle, given by the closest-point projection onto its
     * surface.  The obstacle occupies one side of the surface; its outward
     * normal points to the free side, where the bodies are.
     */
    template <int dim>
    class RigidObstacle
    {
    public:
      virtual ~RigidObstacle() = default;

      /**
       * For a point x of a body: the closest point of the obstacle surface
       * and the obstacle's unit outward normal there.  The signed distance
       * (x - closest) . normal is the initial gap, negative when x lies
       * inside the obstacle.
       */
      virtual void
      project(const dealii::Point<dim> &x,
              dealii::Point<dim>       &closest,
              dealii::Tensor<1, dim>   &normal) const = 0;

      /** A one-line description for the log. */
      virtual std::string
      description() const = 0;
    };


    /** The half-space {y : (y - p) . n <= 0}, n its outward unit normal. */
    template <int dim>
    class PlaneObstacle : public RigidObstacle<dim>
    {
    public:
      PlaneObstacle(const dealii::Point<dim>     &point,
                    const dealii::Tensor<1, dim> &outward_normal);

      void
      project(const dealii::Point<dim> &x,
              dealii::Point<dim>       &closest,
              dealii::Tensor<1, dim>   &normal) const override;

      std::string
      description() const override;

    private:
      dealii::Point<dim>     point_;
      dealii::Tensor<1, dim> normal_;
    };


    /**
     * The region below the graph of a function, {y : y_d <= h(y_1..y_{d-1})}
     * (d = dim, the last coordinate is "up"): a rigid foundation with a
     * curved surface.  The projection is computed by a damped Gauss-Newton
     * iteration on the distance to the graph, started from the vertical
     * projection; h is evaluated by the given function (its gradient by
     * central differences of step @p h_step [m]).
     */
    template <int dim>
    class GraphObstacle : public RigidObstacle<dim>
    {
    public:
      GraphObstacle(std::shared_ptr<const dealii::Function<dim - 1>> height,
                    const std::string                               &expression,
                    const double h_step = 1e-7);

      void
      project(const dealii::Point<dim> &x,
              dealii::Point<dim>       &closest,
              dealii::Tensor<1, dim>   &normal) const override;

      std::string
      description() const override;

    private:
      std::shared_ptr<const dealii::Function<dim - 1>> height_;
      std::string                                      expression_;
      double                                           h_step_;
    };
  } // namespace contact
} // namespace dualcontact
