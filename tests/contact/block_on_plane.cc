// Dual contact solves of a block on a rigid plane against closed forms,
// 2D (plane strain) and 3D, Q1:
//  A. top face pushed down by delta > gap, lateral symmetry planes, no
//     friction: uniaxial stress; every dual solver reproduces the linear
//     closed-form displacement (1e-7 relative) and the total contact force
//     E*(delta - gap) |A| (1e-8 relative); the solvers agree to 1e-6;
//  B. top face loaded by a pressure p, bottom touching (gap 0), the body
//     held only by the contact in the vertical direction (a rigid-body mode,
//     SMALSE-M): contact force = p |A| (1e-8), displacement closed form;
//  C. Coulomb with mu = 0 gives the frictionless answer of A (1e-10);
//  D. 2D, no Dirichlet condition at all, pressure p and a shear traction
//     tau on the top, Tresca slip bound g > tau (three rigid-body modes):
//     normal force p L and tangential force tau L balance (1e-8), every
//     tangential multiplier within its bound, and the stick/slip pattern is
//     consistent (stick: no slip; slip: multiplier at the bound, pointing
//     along the slip);
//  E. 3D, orthotropic Tresca (ellipse with semi-axes g and g/2), shear
//     along both tangents: balance, multipliers inside their ellipses,
//     sticking nodes do not slip, slipping nodes slip along the ellipse's
//     outward normal (the normality rule);
//  F. 2D Coulomb (mu = 0.3, shear 0.2 p): the fixed point converges in a
//     few Tresca solves, forces balance, |lambda_T| <= mu lambda_N.

#include <deal.II/base/function.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/vector_tools.h>

#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <fem/cholmod_solver.h>

#include <test_tools.h>

#include <iostream>

using namespace dealii;
using namespace dualcontact;

using test_tools::check;

constexpr double E = 2e11, nu = 0.3;

template <int dim>
struct Scene
{
  std::unique_ptr<fem::ElasticBody<dim>>               body;
  std::unique_ptr<contact::ContactDiscretization<dim>> contact;
  std::unique_ptr<contact::DualProblem<dim>>           dual;
};

template <int dim>
Scene<dim>
make_scene(const std::vector<fem::DirichletCondition<dim>> &dirichlet,
           const std::vector<fem::TractionCondition<dim>>  &tractions,
           const double                                     gap,
           const contact::FrictionLaw                      &law,
           const unsigned int                               n = 4)
{
  Scene<dim> scene;
  auto       tria = std::make_shared<Triangulation<dim>>();
  GridGenerator::subdivided_hyper_cube(*tria, n, 0., 1., true);
  for (const auto &cell : tria->active_cell_iterators())
    cell->set_material_id(0);
  scene.body = std::make_unique<fem::ElasticBody<dim>>(
    "block",
    tria,
    1,
    std::map<types::material_id, fem::IsotropicMaterial>{
      {0, fem::IsotropicMaterial(E, nu)}});
  scene.body->set_dirichlet_conditions(dirichlet);
  scene.body->set_traction_conditions(tractions);
  scene.body->setup();
  scene.body->assemble();
  Tensor<1, dim> up;
  up[dim - 1] = 1;
  Point<dim> p0;
  p0[dim - 1] = -gap;
  contact::ContactPair<dim> pair;
  pair.name           = "block-plane";
  pair.slave_boundary = 2 * (dim - 1);
  pair.obstacle       = std::make_shared<contact::PlaneObstacle<dim>>(p0, up);
  pair.friction       = law;
  pair.first_tangent_direction[0] = 1;
  scene.contact = std::make_unique<contact::ContactDiscretization<dim>>(
    std::vector<const fem::ElasticBody<dim> *>{scene.body.get()},
    std::vector<contact::ContactPair<dim>>{pair});
  scene.dual = std::make_unique<contact::DualProblem<dim>>(
    std::vector<const fem::ElasticBody<dim> *>{scene.body.get()},
    *scene.contact,
    [] { return std::make_unique<fem::CholmodSolver>(); });
  return scene;
}

template <int dim>
typename contact::ContactSolver<dim>::Result
run_solver(Scene<dim>        &scene,
           const std::string &solver,
           const double       tol = 1e-11)
{
  qp::SolverParameters parameters;
  parameters.solver         = solver;
  parameters.tolerance      = tol;
  parameters.max_iterations = 100000;
  contact::ContactSolver<dim> contact_solver(*scene.dual, parameters, {}, {});
  return contact_solver.solve();
}

/** Linear uniaxial-stress field: vertical strain eps, bottom at -gap. */
template <int dim>
class Uniaxial : public Function<dim>
{
public:
  Uniaxial(const double eps, const double shift)
      : Function<dim>(dim)
      , eps(eps)
      , shift(shift)
  {
  }
  double
  value(const Point<dim> &x, const unsigned int c) const override
  {
    // lateral strain: plane strain -nu/(1-nu) eps, 3D -nu eps
    const double lateral = dim == 2 ? -nu / (1 - nu) * eps : -nu * eps;
    return c == dim - 1 ? shift + eps * x[dim - 1] : lateral * x[c];
  }
  const double eps, shift;
};

template <int dim>
double
relative_error(const fem::ElasticBody<dim> &body,
               const Vector<double>        &u,
               const Function<dim>         &exact)
{
  Vector<double> reference(body.n_dofs());
  VectorTools::interpolate(body.mapping(),
                           body.dof_handler(),
                           exact,
                           reference);
  reference -= u;
  return reference.linfty_norm() / u.linfty_norm();
}

template <int dim>
void
run()
{
  std::cout << dim << "D" << std::endl;
  const double modulus = dim == 2 ? E / (1 - nu * nu) : E;
  const auto   zero    = std::make_shared<Functions::ZeroFunction<dim>>(dim);
  std::vector<fem::DirichletCondition<dim>> symmetry;
  for (unsigned int d = 0; d + 1 < dim; ++d)
  {
    ComponentMask mask(dim, false);
    mask.set(d, true);
    symmetry.push_back({static_cast<types::boundary_id>(2 * d), mask, zero});
  }
  const types::boundary_id top = 2 * dim - 1;

  // A
  const double gap = 1e-4, delta = 3e-4;
  {
    auto          conditions = symmetry;
    ComponentMask vertical(dim, false);
    vertical.set(dim - 1, true);
    std::vector<double> value(dim, 0.);
    value[dim - 1] = -delta;
    conditions.push_back(
      {top,
       vertical,
       std::make_shared<Functions::ConstantFunction<dim>>(value)});
    auto                scene = make_scene<dim>(conditions, {}, gap, {});
    const Uniaxial<dim> exact(-(delta - gap), -gap);
    Vector<double>      first;
    for (const std::string solver :
         {"mprgp", "mpgp", "mpgp-bb", "mwpgp", "spg-qp", "pbbf", "apgd"})
    {
      const auto result = run_solver(scene, solver);
      double     force  = 0;
      for (unsigned int i = 0; i < scene.contact->n_nodes(); ++i)
        force += result.lambda(i);
      const double expected = modulus * (delta - gap);
      const double error =
        relative_error(*scene.body, result.displacements[0], exact);
      check(result.converged && error < 1e-7 &&
              std::abs(force - expected) < 1e-8 * expected,
            "A " + solver + ": " + result.reason + ", " +
              std::to_string(result.qp_statistics[0].iterations) +
              " iterations, force error " +
              std::to_string((force - expected) / expected) +
              ", displacement error",
            error);
      if (first.size() == 0)
        first = result.displacements[0];
      Vector<double> diff = result.displacements[0];
      diff -= first;
      check(diff.linfty_norm() < 1e-6 * first.linfty_norm(),
            "A " + solver + " agrees with mprgp",
            diff.linfty_norm() / first.linfty_norm());
    }
    // C: Coulomb, mu = 0
    contact::FrictionLaw coulomb;
    coulomb.type           = contact::FrictionLaw::Type::coulomb_isotropic;
    coulomb.first          = 0;
    auto           scene_c = make_scene<dim>(conditions, {}, gap, coulomb);
    const auto     result  = run_solver(scene_c, dim == 2 ? "mprgp" : "mpgp");
    Vector<double> diff    = result.displacements[0];
    diff -= first;
    check(result.converged && diff.linfty_norm() < 1e-9 * first.linfty_norm(),
          "C Coulomb mu = 0 vs frictionless (" + result.reason + ")",
          diff.linfty_norm() / first.linfty_norm());
  }

  // B
  {
    const double        p = 1e7;
    std::vector<double> traction(dim, 0.);
    traction[dim - 1] = -p;
    auto scene        = make_scene<dim>(
      symmetry,
      {{top, std::make_shared<Functions::ConstantFunction<dim>>(traction)}},
      0.,
      {});
    check(scene.dual->n_rigid_body_modes() == 1,
          "B rigid-body modes",
          scene.dual->n_rigid_body_modes());
    const auto result = run_solver(scene, "mprgp");
    double     force  = 0;
    for (unsigned int i = 0; i < scene.contact->n_nodes(); ++i)
      force += result.lambda(i);
    const Uniaxial<dim> exact(-p / modulus, 0.);
    const double        error =
      relative_error(*scene.body, result.displacements[0], exact);
    check(result.converged && std::abs(force - p) < 1e-8 * p && error < 1e-6,
          "B SMALSE-M(mprgp): " + result.reason + ", force error " +
            std::to_string((force - p) / p) + ", displacement error",
          error);
  }
}

void
run_tresca_2d()
{
  std::cout << "2D Tresca" << std::endl;
  const double         p = 1e7, tau = 2e6, g = 3e6;
  contact::FrictionLaw law;
  law.type   = contact::FrictionLaw::Type::tresca_isotropic;
  law.first  = g;
  auto scene = make_scene<2>({},
                             {{3,
                               std::make_shared<Functions::ConstantFunction<2>>(
                                 std::vector<double>{tau, -p})}},
                             0.,
                             law,
                             8);
  check(scene.dual->n_rigid_body_modes() == 3,
        "D rigid-body modes",
        scene.dual->n_rigid_body_modes());
  for (const std::string solver : {"mprgp", "mpgp"})
  {
    const auto         result = run_solver(scene, solver, 1e-10);
    const unsigned int n      = scene.contact->n_nodes();
    double       normal = 0, tangential = 0, worst_bound = 0, worst_pattern = 0;
    unsigned int n_slip = 0;
    Vector<double> slip(n);
    Vector<double> u(scene.contact->n_dofs());
    u = result.displacements[0];
    scene.contact->tangential_matrix().vmult(slip, u);
    double slip_scale = 0;
    for (unsigned int i = 0; i < n; ++i)
      slip_scale = std::max(slip_scale, std::abs(slip(i)));
    slip_scale = std::max(slip_scale, result.displacements[0].linfty_norm());
    for (unsigned int i = 0; i < n; ++i)
    {
      normal += result.lambda(i);
      const double lt  = result.lambda(n + i);
      const double psi = scene.dual->slip_bounds_first()[i];
      tangential += lt;
      worst_bound = std::max(worst_bound, (std::abs(lt) - psi) / psi);
      if (std::abs(lt) < (1 - 1e-6) * psi) // stick: no slip
        worst_pattern = std::max(worst_pattern, std::abs(slip(i)) / slip_scale);
      else
      {
        ++n_slip;
        if (std::abs(slip(i)) > 1e-8 * slip_scale && slip(i) * lt < 0)
          worst_pattern = 1;
      }
    }
    check(result.converged && std::abs(normal - p) < 1e-8 * p &&
            std::abs(tangential - tau) < 1e-8 * p,
          "D " + solver + ": " + result.reason + ", slipping nodes " +
            std::to_string(n_slip) + "/" + std::to_string(n) +
            ", force balance error",
          std::max(std::abs(normal - p), std::abs(tangential - tau)) / p);
    check(worst_bound < 1e-9,
          "D " + solver + ": max (|lambda_T| - psi)/psi",
          worst_bound);
    check(worst_pattern < 1e-6,
          "D " + solver + ": stick/slip consistency",
          worst_pattern);
  }
}

void
run_orthotropic_3d()
{
  std::cout << "3D orthotropic Tresca" << std::endl;
  // Slip bounds g1 along x, g2 = g1 / 2 along y; the shear (tau_x, tau_y)
  // uses 80% of the elliptic capacity, so the block holds but edge nodes
  // slip.
  const double p = 1e7, g1 = 4e6, g2 = 2e6;
  const double tau_x = 0.8 * g1 * std::cos(0.6),
               tau_y = 0.8 * g2 * std::sin(0.6);
  contact::FrictionLaw law;
  law.type   = contact::FrictionLaw::Type::tresca_orthotropic;
  law.first  = g1;
  law.second = g2;
  auto scene = make_scene<3>({},
                             {{5,
                               std::make_shared<Functions::ConstantFunction<3>>(
                                 std::vector<double>{tau_x, tau_y, -p})}},
                             0.,
                             law,
                             4);
  for (const std::string solver : {"mpgp", "spg-qp"})
  {
    const auto         result = run_solver(scene, solver, 1e-10);
    const unsigned int n      = scene.contact->n_nodes();
    Vector<double>     slip(2 * n);
    scene.contact->tangential_matrix().vmult(slip, result.displacements[0]);
    const double scale = result.displacements[0].linfty_norm();
    Tensor<1, 3> force;
    double       worst_bound = 0, worst_pattern = 0;
    unsigned int n_slip = 0;
    for (unsigned int i = 0; i < n; ++i)
    {
      const auto &node = scene.contact->nodes()[i];
      force += result.lambda(i) * node.normal;
      const double l1 = result.lambda(n + 2 * i),
                   l2 = result.lambda(n + 2 * i + 1);
      force += l1 * node.tangents[0] + l2 * node.tangents[1];
      const double utilization =
        scene.dual->friction_utilization(result.lambda, i);
      worst_bound     = std::max(worst_bound, utilization - 1);
      const double s1 = slip(2 * i), s2 = slip(2 * i + 1);
      const double s = std::hypot(s1, s2);
      if (utilization < 1 - 1e-6)
        worst_pattern = std::max(worst_pattern, s / scale);
      else if (s > 1e-8 * scale)
      {
        ++n_slip;
        // normality: slip along the ellipse's outward normal
        const double psi1 = scene.dual->slip_bounds_first()[i];
        const double psi2 = scene.dual->slip_bounds_second()[i];
        const double m1 = l1 / (psi1 * psi1), m2 = l2 / (psi2 * psi2);
        const double cosine = (m1 * s1 + m2 * s2) / (std::hypot(m1, m2) * s);
        worst_pattern       = std::max(worst_pattern, 1 - cosine);
      }
    }
    // contact force on the body is -force; it balances the applied load
    Tensor<1, 3> applied = scene.body->applied_force();
    const double balance = (applied - force).norm() / p;
    check(result.converged && balance < 1e-8,
          "E " + solver + ": " + result.reason + ", slipping nodes " +
            std::to_string(n_slip) + "/" + std::to_string(n) +
            ", force balance error",
          balance);
    check(worst_bound < 1e-9,
          "E " + solver + ": max ellipse norm - 1",
          worst_bound);
    check(n_slip > 0 && worst_pattern < 1e-5,
          "E " + solver + ": stick without slip, slip along the ellipse normal",
          worst_pattern);
  }
}


void
run_coulomb_2d()
{
  std::cout << "2D Coulomb" << std::endl;
  // mu = 0.3, shear 0.2 p on the top: the block holds, edge nodes slip.
  const double         p = 1e7, mu = 0.3, tau = 0.2 * p;
  contact::FrictionLaw law;
  law.type                  = contact::FrictionLaw::Type::coulomb_isotropic;
  law.first                 = mu;
  auto               scene  = make_scene<2>({},
                             {{3,
                                              std::make_shared<Functions::ConstantFunction<2>>(
                                 std::vector<double>{tau, -p})}},
                             0.,
                             law,
                             8);
  const auto         result = run_solver(scene, "mprgp", 1e-10);
  const unsigned int n      = scene.contact->n_nodes();
  double             normal = 0, tangential = 0, worst_cone = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    normal += result.lambda(i);
    tangential += result.lambda(n + i);
    worst_cone =
      std::max(worst_cone,
               std::abs(result.lambda(n + i)) - mu * result.lambda(i));
  }
  check(result.converged && result.qp_statistics.size() > 2 &&
          result.coulomb_changes.back() <= 1e-6,
        "F Coulomb: " + result.reason + ", fixed-point iterations " +
          std::to_string(result.qp_statistics.size()) + ", last change",
        result.coulomb_changes.back());
  check(std::abs(normal - p) < 1e-8 * p &&
          std::abs(tangential - tau) < 1e-8 * p,
        "F balance error",
        std::max(std::abs(normal - p), std::abs(tangential - tau)) / p);
  // psi was updated from the previous iterate, so the cone holds to the
  // fixed-point tolerance
  check(worst_cone < 1e-5 * p / n,
        "F max (|lambda_T| - mu lambda_N) / (p / n)",
        worst_cone / (p / n));
}


int
main()
{
  try
  {
    run<2>();
    run<3>();
    run_tresca_2d();
    run_orthotropic_3d();
    run_coulomb_2d();
  }
  catch (const std::exception &e)
  {
    std::cerr << "exception: " << e.what() << std::endl;
    return 1;
  }
  return test_tools::finish();
}
