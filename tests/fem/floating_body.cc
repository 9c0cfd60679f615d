// A floating body (no Dirichlet condition) pulled by equal and opposite
// tractions sigma on its end faces x = 0 and x = L: the stiffness matrix is
// singular with the rigid-body motions as kernel.  Checks: the modes are
// orthonormal and K R = 0; the fixing-dof generalized inverse gives u with
// K u = f (f is balanced, so in the range of K); the strain energy equals the
// closed form of uniaxial stress sigma^2 V / (2 E') (E' = E in 3D,
// E / (1 - nu^2) in plane strain); K K^# K v = K v for a random v; given
// the kernel, the pseudoinverse K^+ (K K^+ b = b - R R'b, R'K^+ b = 0,
// K^+ K v = v - R R'v, where K^# leaves a rigid motion).

#include <deal.II/base/function.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <fem/cholmod_solver.h>
#include <fem/elastic_body.h>
#include <fem/generalized_inverse.h>
#include <fem/rigid_body_modes.h>

#include <test_tools.h>

#include <iostream>
#include <random>

using namespace dealii;
using namespace dualcontact;

using test_tools::check;

/** ||a - b|| / ||b||. */
double
relative_difference(Vector<double> a, const Vector<double> &b)
{
  a -= b;
  return a.l2_norm() / b.l2_norm();
}

template <int dim>
void
run(const unsigned int degree)
{
  std::cout << dim << "D Q" << degree << std::endl;
  auto       tria = std::make_shared<Triangulation<dim>>();
  Point<dim> p2;
  p2[0] = 3;
  for (unsigned int d = 1; d < dim; ++d)
    p2[d] = 1;
  std::vector<unsigned int> subdivisions(dim, 2);
  subdivisions[0] = 6;
  GridGenerator::subdivided_hyper_rectangle(
    *tria, subdivisions, Point<dim>(), p2, true);
  for (const auto &cell : tria->active_cell_iterators())
    cell->set_material_id(0);
  // Refine one corner so that hanging nodes are present too.
  tria->begin_active()->set_refine_flag();
  tria->execute_coarsening_and_refinement();

  const double                 E = 7e10, nu = 0.33, sigma = 2e7;
  const fem::IsotropicMaterial material(E, nu);
  fem::ElasticBody<dim>        body("floating", tria, degree, {{0, material}});
  std::vector<double>          t0(dim, 0.), t1(dim, 0.);
  t0[0] = -sigma;
  t1[0] = sigma;
  body.set_traction_conditions(
    {{0, std::make_shared<Functions::ConstantFunction<dim>>(t0)},
     {1, std::make_shared<Functions::ConstantFunction<dim>>(t1)}});
  body.setup();
  body.assemble();
  const SparseMatrix<double> &K = body.stiffness_matrix();

  const fem::RigidBodyModes<dim> rbm(body);
  double                         max_orth = 0, max_kernel = 0;
  Vector<double>                 Kr(body.n_dofs());
  for (unsigned int k = 0; k < rbm.n_modes(); ++k)
  {
    for (unsigned int j = 0; j < rbm.n_modes(); ++j)
      max_orth = std::max(max_orth,
                          std::abs(rbm.modes()[k] * rbm.modes()[j] -
                                   (k == j ? 1. : 0.)));
    K.vmult(Kr, rbm.modes()[k]);
    max_kernel = std::max(max_kernel, Kr.l2_norm() / K.linfty_norm());
  }
  check(max_orth < 1e-12, "R'R = I, max deviation", max_orth);
  check(max_kernel < 1e-10, "||K r_k|| / ||K||_inf", max_kernel);

  fem::GeneralizedInverse solver(std::make_unique<fem::CholmodSolver>(),
                                 rbm.fixing_dofs());
  solver.initialize(K);
  Vector<double> u, residual(body.n_dofs());
  solver.solve(u, body.load_vector());
  K.vmult(residual, u);
  const double residual_error =
    relative_difference(residual, body.load_vector());
  check(residual_error < 1e-10, "||K K^# f - f|| / ||f||", residual_error);

  body.distribute(u);
  const double volume   = GridTools::volume(*tria);
  const double modulus  = dim == 3 ? E : E / (1 - nu * nu);
  const double expected = sigma * sigma * volume / (2 * modulus);
  const double energy   = body.strain_energy(u);
  check(std::abs(energy - expected) < 1e-10 * expected,
        "strain energy / closed form - 1",
        energy / expected - 1);

  std::mt19937                           rng(3);
  std::uniform_real_distribution<double> uniform(-1, 1);
  Vector<double> v(body.n_dofs()), Kv(body.n_dofs()), w(body.n_dofs()),
    Kw(body.n_dofs());
  for (auto &entry : v)
    entry = uniform(rng);
  K.vmult(Kv, v);
  solver.solve(w, Kv);
  K.vmult(Kw, w);
  const double generalized_error = relative_difference(Kw, Kv);
  check(generalized_error < 1e-9,
        "||K K^# K v - K v|| / ||K v||",
        generalized_error);

  // Given the kernel, solve() applies the Moore-Penrose pseudoinverse
  // K^+ = (I - R R') K^# (I - R R'): K K^+ b = b - R R'b for any b (not
  // only balanced ones), R'K^+ b = 0, and K^+ K v = v - R R'v.  K^#
  // answers with an extra rigid motion, so it fails the second.
  fem::GeneralizedInverse pseudoinverse(std::make_unique<fem::CholmodSolver>(),
                                        rbm.fixing_dofs(),
                                        rbm.modes());
  pseudoinverse.initialize(K);
  const auto remove_kernel = [&rbm](Vector<double> &x)
  {
    for (const auto &r : rbm.modes())
      x.add(-(r * x), r);
  };
  const auto largest_kernel_part = [&rbm](const Vector<double> &x)
  {
    double largest = 0;
    for (const auto &r : rbm.modes())
      largest = std::max(largest, std::abs(r * x) / x.l2_norm());
    return largest;
  };
  Vector<double> b(body.n_dofs()), x(body.n_dofs()), Kx(body.n_dofs());
  for (auto &entry : b)
    entry = uniform(rng);
  pseudoinverse.solve(x, b);
  K.vmult(Kx, x);
  Vector<double> range_part = b;
  remove_kernel(range_part);
  const double range_error = relative_difference(Kx, range_part);
  check(range_error < 1e-9,
        "||K K^+ b - (b - R R'b)|| / ||b - R R'b||",
        range_error);
  check(largest_kernel_part(x) < 1e-12,
        "max_k |r_k' K^+ b| / ||K^+ b||",
        largest_kernel_part(x));
  Vector<double> x_sharp(body.n_dofs());
  pseudoinverse.solve_fixing_dofs(x_sharp, range_part);
  check(largest_kernel_part(x_sharp) > 1e-3,
        "K^# b carries a rigid motion: max_k |r_k' K^# b| / ||K^# b||",
        largest_kernel_part(x_sharp));
  pseudoinverse.solve(x, Kv);
  Vector<double> expected_x = v;
  remove_kernel(expected_x);
  const double projection_error = relative_difference(x, expected_x);
  check(projection_error < 1e-8,
        "||K^+ K v - (v - R R'v)|| / ||v - R R'v||",
        projection_error);
}

// Partially supported bodies: the kernel is what the supports allow.
template <int dim>
void
run_supports()
{
  std::cout << dim << "D supports" << std::endl;
  auto tria = std::make_shared<Triangulation<dim>>();
  GridGenerator::hyper_cube(*tria, 0, 1, true);
  tria->refine_global(2);
  const fem::IsotropicMaterial material(1e9, 0.3);
  const auto zero = std::make_shared<Functions::ZeroFunction<dim>>(dim);
  // roller: normal component fixed on the bottom face
  ComponentMask normal_only(dim, false);
  normal_only.set(dim - 1, true);
  const std::vector<
    std::pair<std::vector<fem::DirichletCondition<dim>>, unsigned int>>
    cases = {{{}, dim * (dim + 1) / 2},
             {{{2 * (dim - 1), normal_only, zero}}, dim == 2 ? 1u : 3u},
             {{{0, ComponentMask(dim, true), zero}}, 0u}};
  for (const auto &[conditions, expected] : cases)
  {
    fem::ElasticBody<dim> body("supports", tria, 1, {{0, material}});
    body.set_dirichlet_conditions(conditions);
    body.setup();
    body.assemble();
    const fem::RigidBodyModes<dim> rbm(body);
    double                         max_kernel = 0;
    Vector<double>                 Kr(body.n_dofs());
    for (const auto &mode : rbm.modes())
    {
      body.stiffness_matrix().vmult(Kr, mode);
      max_kernel =
        std::max(max_kernel,
                 Kr.l2_norm() / body.stiffness_matrix().linfty_norm());
    }
    check(rbm.n_modes() == expected && rbm.fixing_dofs().size() == expected &&
            max_kernel < 1e-10,
          std::to_string(conditions.size()) + " condition(s): modes " +
            std::to_string(rbm.n_modes()) + " (expected " +
            std::to_string(expected) + "), max ||K r|| / ||K||",
          max_kernel);
  }
}

int
main()
{
  try
  {
    run<2>(1);
    run<2>(2);
    run<3>(1);
    run<3>(2);
    run_supports<2>();
    run_supports<3>();
  }
  catch (const std::exception &e)
  {
    std::cerr << "exception: " << e.what() << std::endl;
    return 1;
  }
  return test_tools::finish();
}
