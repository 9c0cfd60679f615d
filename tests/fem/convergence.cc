// Convergence against a manufactured solution: u_c(x) = a_c prod_d
// sin(k_cd x_d + phi_cd) on the unit square / cube, the body force
// b = -div sigma(u) computed from its exact second derivatives, u prescribed
// on the whole boundary.  Measured on a sequence of uniformly refined meshes:
// the L2 error of u and the energy-norm error (int eps(e) : C : eps(e))^1/2.
// Asserted: the rates of the last two levels are within 0.1 of p + 1 (L2) and
// p (energy) for Q1 and Q2 on squares / cubes and for P1 and P2 on
// triangles / tetrahedra (the same boxes split into 2 / 5 simplices), in 2D
// and 3D.

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/vector_tools.h>

#include <fem/cholmod_solver.h>
#include <fem/elastic_body.h>

#include <cmath>
#include <iomanip>
#include <iostream>

using namespace dealii;
using namespace dualcontact;

namespace
{
  constexpr double amplitude = 1e-3;

  /** The exact displacement with its gradient and Hessian. */
  template <int dim>
  class ExactDisplacement : public Function<dim>
  {
  public:
    ExactDisplacement()
        : Function<dim>(dim)
    {
    }

    double
    k(const unsigned int c, const unsigned int d) const
    {
      return numbers::PI * (0.5 + 0.25 * ((c + 2 * d) % 3));
    }
    double
    phi(const unsigned int c, const unsigned int d) const
    {
      return 0.3 + 0.2 * c + 0.1 * d;
    }

    double
    value(const Point<dim> &x, const unsigned int c) const override
    {
      double v = amplitude * (1. + c);
      for (unsigned int d = 0; d < dim; ++d)
        v *= std::sin(k(c, d) * x[d] + phi(c, d));
      return v;
    }

    Tensor<1, dim>
    gradient(const Point<dim> &x, const unsigned int c) const override
    {
      Tensor<1, dim> g;
      for (unsigned int i = 0; i < dim; ++i)
      {
        double v = amplitude * (1. + c);
        for (unsigned int d = 0; d < dim; ++d)
          v *= (d == i) ? k(c, d) * std::cos(k(c, d) * x[d] + phi(c, d)) :
                          std::sin(k(c, d) * x[d] + phi(c, d));
        g[i] = v;
      }
      return g;
    }

    SymmetricTensor<2, dim>
    hessian(const Point<dim> &x, const unsigned int c) const override
    {
      SymmetricTensor<2, dim> h;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
        {
          double v = amplitude * (1. + c);
          for (unsigned int d = 0; d < dim; ++d)
          {
            const double s  = std::sin(k(c, d) * x[d] + phi(c, d));
            const double co = std::cos(k(c, d) * x[d] + phi(c, d));
            if (d == i && d == j)
              v *= -k(c, d) * k(c, d) * s;
            else if (d == i || d == j)
              v *= k(c, d) * co;
            else
              v *= s;
          }
          h[i][j] = v;
        }
      return h;
    }
  };

  /** b = -div sigma(u) = -(mu Laplace u + (lambda + mu) grad div u). */
  template <int dim>
  class BodyForce : public Function<dim>
  {
  public:
    BodyForce(const fem::IsotropicMaterial &material)
        : Function<dim>(dim)
        , lambda(material.lame_lambda())
        , mu(material.shear_modulus())
    {
    }
    double
    value(const Point<dim> &x, const unsigned int i) const override
    {
      double                        laplace = 0, grad_div = 0;
      const SymmetricTensor<2, dim> hi = exact.hessian(x, i);
      for (unsigned int j = 0; j < dim; ++j)
      {
        laplace += hi[j][j];
        grad_div += exact.hessian(x, j)[i][j];
      }
      return -(mu * laplace + (lambda + mu) * grad_div);
    }
    ExactDisplacement<dim> exact;
    const double           lambda, mu;
  };

  int failures = 0;

  template <int dim>
  void
  run(const unsigned int degree,
      const unsigned int first_level,
      const unsigned int last_level,
      const bool         simplex = false)
  {
    const fem::IsotropicMaterial material(1e9, 0.3);
    auto                exact = std::make_shared<ExactDisplacement<dim>>();
    std::vector<double> h, l2, energy;
    std::cout << dim << "D " << (simplex ? "P" : "Q") << degree << ":\n"
              << "      h       dofs    L2 error  energy error" << std::endl;
    for (unsigned int level = first_level; level <= last_level; ++level)
    {
      auto tria = std::make_shared<Triangulation<dim>>();
      if (simplex)
        GridGenerator::subdivided_hyper_cube_with_simplices(*tria,
                                                            1u << level);
      else
      {
        GridGenerator::hyper_cube(*tria, 0., 1.);
        tria->refine_global(level);
      }
      fem::ElasticBody<dim> body("manufactured", tria, degree, {{0, material}});
      body.set_dirichlet_conditions({{0, ComponentMask(dim, true), exact}});
      body.set_body_force(std::make_shared<BodyForce<dim>>(material));
      body.setup();
      body.assemble();
      fem::CholmodSolver solver;
      Vector<double>     u;
      body.solve(solver, u);

      const Quadrature<dim>                    quadrature =
        body.cell_family().cell_quadrature(degree + 2);
      FEValues<dim>                            fe_values(body.mapping(),
                              body.fe(),
                              quadrature,
                              update_values | update_gradients |
                                update_quadrature_points | update_JxW_values);
      std::vector<Vector<double>>              values(quadrature.size(),
                                         Vector<double>(dim));
      std::vector<std::vector<Tensor<1, dim>>> gradients(
        quadrature.size(), std::vector<Tensor<1, dim>>(dim));
      double l2_sq = 0, energy_sq = 0;
      for (const auto &cell : body.dof_handler().active_cell_iterators())
      {
        fe_values.reinit(cell);
        fe_values.get_function_values(u, values);
        fe_values.get_function_gradients(u, gradients);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          const Point<dim> &x = fe_values.quadrature_point(q);
          Tensor<2, dim>    grad_e;
          for (unsigned int c = 0; c < dim; ++c)
          {
            const double e = values[q][c] - exact->value(x, c);
            l2_sq += e * e * fe_values.JxW(q);
            grad_e[c] = gradients[q][c] - exact->gradient(x, c);
          }
          const SymmetricTensor<2, dim> eps = symmetrize(grad_e);
          energy_sq += (material.stress<dim>(eps) * eps) * fe_values.JxW(q);
        }
      }
      h.push_back(1. / (1u << level));
      l2.push_back(std::sqrt(l2_sq));
      energy.push_back(std::sqrt(energy_sq));
      std::cout << std::setw(9) << h.back() << std::setw(9) << body.n_dofs()
                << std::scientific << std::setprecision(3) << std::setw(12)
                << l2.back() << std::setw(12) << energy.back()
                << std::defaultfloat << std::endl;
    }
    const std::size_t n = h.size();
    const double      l2_rate =
      std::log(l2[n - 2] / l2[n - 1]) / std::log(h[n - 2] / h[n - 1]);
    const double energy_rate =
      std::log(energy[n - 2] / energy[n - 1]) / std::log(h[n - 2] / h[n - 1]);
    const bool ok = std::abs(l2_rate - (degree + 1.)) < 0.1 &&
                    std::abs(energy_rate - degree) < 0.1;
    std::cout << "  rates: L2 " << std::fixed << std::setprecision(3) << l2_rate
              << " (expected " << degree + 1 << "), energy " << energy_rate
              << " (expected " << degree << ")  " << (ok ? "ok" : "FAIL")
              << std::defaultfloat << std::endl;
    if (!ok)
      ++failures;
  }
} // namespace

int
main()
{
  try
  {
    run<2>(1, 3, 6);
    run<2>(2, 2, 5);
    run<3>(1, 2, 4);
    run<3>(2, 1, 3);
    run<2>(1, 3, 6, true);
    run<2>(2, 2, 5, true);
    run<3>(1, 2, 4, true);
    run<3>(2, 1, 3, true);
  }
  catch (const std::exception &e)
  {
    std::cerr << "exception: " << e.what() << std::endl;
    return 1;
  }
  std::cout << (failures == 0 ? "all checks passed" : "FAILED") << std::endl;
  return failures == 0 ? 0 : 1;
}
