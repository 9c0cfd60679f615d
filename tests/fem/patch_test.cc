// Patch test: a linear displacement field u(x) = A x + c is in the finite
// element space on any mesh of straight-sided cells, so the discrete solution
// must reproduce it to round-off and the stress must be the constant
// C : sym(A).  Checked in 2D and 3D, for Q1 and Q2, on randomly distorted
// meshes, with (a) the field prescribed on the whole boundary and (b) the
// field prescribed on one face and the tractions sigma n on all others.
// Also checks equilibrium (reactions + applied loads = 0) and the energy
// 1/2 sigma : eps |Omega|.

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <fem/cholmod_solver.h>
#include <fem/elastic_body.h>

#include <iomanip>
#include <iostream>
#include <sstream>

using namespace dealii;
using namespace dualcontact;

namespace
{
  template <int dim>
  Tensor<2, dim>
  gradient_of_field()
  {
    Tensor<2, dim> A;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        A[i][j] = 1e-3 * (1. + i + 2. * j) * ((i + j) % 2 ? -1. : 1.);
    return A;
  }

  template <int dim>
  class LinearField : public Function<dim>
  {
  public:
    LinearField()
        : Function<dim>(dim)
        , A(gradient_of_field<dim>())
    {
    }
    double
    value(const Point<dim> &x, const unsigned int c) const override
    {
      return A[c] * x + 1e-4 * (c + 1);
    }
    Tensor<2, dim> A;
  };

  int failures = 0;

  std::string
  sci(const double x)
  {
    std::ostringstream out;
    out << std::scientific << std::setprecision(3) << x;
    return out.str();
  }

  void
  check(const bool ok, const std::string &what)
  {
    std::cout << (ok ? "  ok   " : "  FAIL ") << what << std::endl;
    if (!ok)
      ++failures;
  }

  /**
   * The box [0, 1] x [0, 1.5] (x [0, 2]) of 3^dim cells refined once, of
   * hypercubes or of simplices (2 triangles / 5 tetrahedra per cell), with
   * boundary id 2 d at x_d = min and 2 d + 1 at x_d = max.
   */
  template <int dim>
  void
  make_box(Triangulation<dim> &tria, const bool simplex)
  {
    Point<dim> p1, p2;
    for (unsigned int d = 0; d < dim; ++d)
      p2[d] = 1. + 0.5 * d;
    std::vector<unsigned int> subdivisions(dim, 3);
    if (simplex)
      GridGenerator::subdivided_hyper_rectangle_with_simplices(tria,
                                                               subdivisions,
                                                               p1,
                                                               p2);
    else
      GridGenerator::subdivided_hyper_rectangle(
        tria, subdivisions, p1, p2, /*colorize=*/true);
    for (const auto &face : tria.active_face_iterators())
      if (face->at_boundary())
        for (unsigned int d = 0; d < dim; ++d)
        {
          if (std::abs(face->center()[d] - p1[d]) < 1e-12)
            face->set_boundary_id(2 * d);
          if (std::abs(face->center()[d] - p2[d]) < 1e-12)
            face->set_boundary_id(2 * d + 1);
        }
    for (const auto &cell : tria.active_cell_iterators())
      cell->set_material_id(0);
    tria.refine_global(1);
  }

  template <int dim>
  void
  run(const unsigned int degree, const bool with_tractions, const bool simplex)
  {
    std::cout << dim << "D, " << (simplex ? "P" : "Q") << degree
              << (with_tractions ? ", tractions on all faces but one" :
                                   ", Dirichlet on the whole boundary")
              << std::endl;
    auto tria = std::make_shared<Triangulation<dim>>();
    make_box(*tria, simplex);
    GridTools::distort_random(0.3, *tria, /*keep_boundary=*/true, 42);

    const fem::IsotropicMaterial material(2.1e11, 0.29);
    fem::ElasticBody<dim>        body("patch", tria, degree, {{0, material}});

    auto                          field  = std::make_shared<LinearField<dim>>();
    const SymmetricTensor<2, dim> strain = symmetrize(field->A);
    const SymmetricTensor<2, dim> stress = material.stress<dim>(strain);

    std::vector<fem::DirichletCondition<dim>> dirichlet;
    std::vector<fem::TractionCondition<dim>>  tractions;
    for (unsigned int face = 0; face < 2 * dim; ++face)
      if (!with_tractions || face == 0)
        dirichlet.push_back({face, ComponentMask(dim, true), field});
      else
      {
        Tensor<1, dim> normal;
        normal[face / 2]       = (face % 2 == 0) ? -1. : 1.;
        const Tensor<1, dim> t = stress * normal;
        tractions.push_back(
          {face,
           std::make_shared<Functions::ConstantFunction<dim>>(
             std::vector<double>(t.begin_raw(), t.end_raw()))});
      }
    body.set_dirichlet_conditions(dirichlet);
    body.set_traction_conditions(tractions);
    body.setup();
    body.assemble();

    fem::CholmodSolver solver;
    Vector<double>     u;
    body.solve(solver, u);

    Vector<double> exact(body.n_dofs());
    VectorTools::interpolate(body.mapping(), body.dof_handler(), *field, exact);
    Vector<double> error = u;
    error -= exact;
    const double relative = error.linfty_norm() / exact.linfty_norm();
    check(relative < 1e-10,
          "nodal error " + sci(relative) + " relative < 1e-10");

    // Stress at every quadrature point.
    const Quadrature<dim>                quadrature =
      body.cell_family().cell_quadrature(degree + 1);
    check(body.cell_family().is_simplex() == simplex,
          "the body's cells are " + body.cell_family().cells_in_words());
    FEValues<dim>                        fe_values(body.mapping(),
                            body.fe(),
                            quadrature,
                            update_gradients | update_JxW_values);
    std::vector<SymmetricTensor<2, dim>> eps(quadrature.size());
    double                               max_stress_error = 0, volume = 0;
    for (const auto &cell : body.dof_handler().active_cell_iterators())
    {
      fe_values.reinit(cell);
      fe_values[FEValuesExtractors::Vector(0)].get_function_symmetric_gradients(
        u, eps);
      for (unsigned int q = 0; q < quadrature.size(); ++q)
      {
        max_stress_error =
          std::max(max_stress_error,
                   (material.stress<dim>(eps[q]) - stress).norm());
        volume += fe_values.JxW(q);
      }
    }
    max_stress_error /= stress.norm();
    check(max_stress_error < 1e-9,
          "stress constant, relative deviation " + sci(max_stress_error) +
            " < 1e-9");

    const double energy   = body.strain_energy(u);
    const double expected = 0.5 * (stress * strain) * volume;
    check(std::abs(energy - expected) < 1e-10 * expected,
          "strain energy " + sci(energy) + " = 1/2 sigma:eps |V|");

    Tensor<1, dim> balance = body.applied_force();
    for (const auto &[id, reaction] : body.reaction_forces(u))
      balance += reaction;
    // Scale: the traction resultant on one face.
    const double scale = stress.norm() * volume;
    check(balance.norm() < 1e-9 * scale,
          "equilibrium |sum reactions + applied| / scale = " +
            sci(balance.norm() / scale) + " < 1e-9");
  }
} // namespace

int
main()
{
  try
  {
    for (const bool simplex : {false, true})
      for (const unsigned int degree : {1u, 2u})
        for (const bool tractions : {false, true})
        {
          run<2>(degree, tractions, simplex);
          run<3>(degree, tractions, simplex);
        }
  }
  catch (const std::exception &e)
  {
    std::cerr << "exception: " << e.what() << std::endl;
    return 1;
  }
  std::cout << (failures == 0 ? "all checks passed" : "FAILED") << std::endl;
  return failures == 0 ? 0 : 1;
}
