// Round trip of a scene's contact problem through FCLIB files: a 3D block
// (Q1, 4^3 cells) on a rigid plane, its top face moved down and sideways
// (prescribed displacement, so that both offsets of w matter), its side x = 0
// clamped (the contact nodes on that edge are left out of the export),
// isotropic Coulomb friction mu = 0.3 (some nodes stick, some slip).  The scene
// is solved by contact::ContactSolver; its problem is written as an FCLIB
// global and local problem with the solution; both files are read back,
// solved by fclib::LocalSolver, and the contact forces agree with the
// scene's to 1e-8 (relative).  W = F and q = -d are checked against the
// DualProblem, and the export of a Tresca pair is refused with a message.
#include <deal.II/base/function.h>
#include <deal.II/grid/grid_generator.h>

#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <fclib/accuracy.h>
#include <fclib/fclib_file.h>
#include <fclib/local_solver.h>
#include <fclib/scene_export.h>
#include <fem/cholmod_solver.h>
#include <test_tools.h>

#include <filesystem>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

namespace
{
  constexpr int dim = 3;

  struct Scene
  {
    std::unique_ptr<fem::ElasticBody<dim>>               body;
    std::unique_ptr<contact::ContactDiscretization<dim>> contact;
    std::unique_ptr<contact::DualProblem<dim>>           dual;
  };

  Scene
  make_scene(const contact::FrictionLaw &law)
  {
    Scene scene;
    auto  tria = std::make_shared<Triangulation<dim>>();
    GridGenerator::subdivided_hyper_cube(*tria, 4, 0., 1., true);
    for (const auto &cell : tria->active_cell_iterators())
      cell->set_material_id(0);
    scene.body = std::make_unique<fem::ElasticBody<dim>>(
      "block",
      tria,
      1,
      std::map<types::material_id, fem::IsotropicMaterial>{
        {0, fem::IsotropicMaterial(2e11, 0.3)}});
    // top face (id 5): 1e-4 m down, 3e-5 m along x (gap 5e-5 at the bottom)
    fem::DirichletCondition<dim> top;
    top.boundary_id = 5;
    top.components  = ComponentMask(std::vector<bool>{true, true, true});
    top.values      = std::make_shared<Functions::ConstantFunction<dim>>(
      std::vector<double>{3e-5, 0., -1e-4});
    // the face x = 0 (id 0) clamped: its bottom edge nodes are contact
    // nodes with every dof prescribed, which the export leaves out
    fem::DirichletCondition<dim> side;
    side.boundary_id = 0;
    side.components  = ComponentMask(std::vector<bool>{true, true, true});
    side.values      = std::make_shared<Functions::ZeroFunction<dim>>(dim);
    scene.body->set_dirichlet_conditions({top, side});
    scene.body->setup();
    scene.body->assemble();
    Tensor<1, dim> up;
    up[dim - 1] = 1;
    Point<dim> p0;
    p0[dim - 1] = -5e-5;
    contact::ContactPair<dim> pair;
    pair.name           = "block-plane";
    pair.slave_boundary = 4;
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

  double
  relative_difference(const Vector<double> &a, const Vector<double> &b)
  {
    Vector<double> d(a);
    d -= b;
    return d.l2_norm() / b.l2_norm();
  }
} // namespace

int
main()
{
  contact::FrictionLaw law;
  law.type    = contact::FrictionLaw::Type::coulomb_isotropic;
  law.first   = 0.3;
  Scene scene = make_scene(law);

  qp::SolverParameters qp_parameters;
  qp_parameters.solver         = "mpgp";
  qp_parameters.tolerance      = 1e-12;
  qp_parameters.max_iterations = 100000;
  contact::CoulombParameters coulomb;
  coulomb.tolerance      = 1e-11;
  coulomb.max_iterations = 200;
  contact::ContactSolver<dim> solver(*scene.dual, qp_parameters, {}, coulomb);
  const auto                  result = solver.solve();
  check(result.converged, "scene solved", result.reason);

  const Vector<double> r =
    fclib::to_fclib_layout(*scene.contact, *scene.dual, result.lambda);
  // 25 nodes on the bottom face, the 5 on the clamped edge left out
  const unsigned int nodes = fclib::exported_nodes(*scene.contact).size();
  check(scene.contact->n_nodes() == 25 && nodes == 20,
        "exported contact nodes (of 25)",
        nodes);
  unsigned int n_stick = 0, n_slip = 0;
  for (unsigned int i = 0; i < nodes; ++i)
    if (r(3 * i) > 0)
    {
      const double t = std::hypot(r(3 * i + 1), r(3 * i + 2));
      (t < 0.3 * r(3 * i) * (1 - 1e-6) ? n_stick : n_slip) += 1;
    }
  check(n_stick > 0 && n_slip > 0,
        "the scene has sticking and slipping nodes (stick, slip)",
        std::to_string(n_stick) + ", " + std::to_string(n_slip));

  const fclib::GlobalProblem global = fclib::make_global_problem<dim>(
    {scene.body.get()}, *scene.contact, *scene.dual, "block on a plane");
  const fclib::LocalProblem local = global.reduce_to_local();

  // W = F and q = -d (layouts converted)
  {
    Vector<double> x(local.size()), Wx(local.size()), Fx;
    for (unsigned int i = 0; i < x.size(); ++i)
      x(i) = std::sin(1. + i);
    // frictionless tangents are absent from F: every node is frictional here
    const Vector<double> x_dual =
      fclib::to_dual_layout(*scene.contact, *scene.dual, x);
    Fx.reinit(x_dual.size());
    scene.dual->apply_F(Fx, x_dual);
    local.W().vmult(Wx, x);
    check(relative_difference(
            Wx, fclib::to_fclib_layout(*scene.contact, *scene.dual, Fx)) <
            1e-10,
          "W x = F x",
          relative_difference(
            Wx, fclib::to_fclib_layout(*scene.contact, *scene.dual, Fx)));
    Vector<double> minus_d =
      fclib::to_fclib_layout(*scene.contact, *scene.dual, scene.dual->d());
    minus_d *= -1;
    check(relative_difference(local.q(), minus_d) < 1e-10,
          "q = -d",
          relative_difference(local.q(), minus_d));
  }
  check(fclib::fclib_error(local, r) < 1e-8,
        "FCLIB error of the scene's solution",
        fclib::fclib_error(local, r));

  const std::string global_file = "scene_round_trip_global.hdf5";
  const std::string local_file  = "scene_round_trip_local.hdf5";
  fclib::write_global(global_file, global, r, "test");
  fclib::write_local(local_file, local, r, "test");

  for (const std::string &file : {global_file, local_file})
  {
    const fclib::LocalProblem back = fclib::read_as_local(file);
    check(back.n_contacts() == nodes && back.mu()[0] == 0.3,
          file + ": contacts",
          back.n_contacts());
    const Vector<double> stored = fclib::read_solution_r(file);
    check(stored.size() == r.size() && relative_difference(stored, r) == 0,
          file + ": stored solution",
          stored.size());
    fclib::LocalSolver s(back,
                         qp_parameters,
                         coulomb,
                         fclib::Model::coulomb_fixed_point);
    Vector<double>     r_back(back.size());
    const auto         solved = s.solve(r_back);
    check(solved.converged, file + ": solved", solved.reason);
    check(relative_difference(r_back, r) < 1e-8,
          file + ": ||r - r_scene|| / ||r_scene||",
          relative_difference(r_back, r));
    check(solved.fclib_error < 1e-8,
          file + ": FCLIB error",
          solved.fclib_error);
    std::filesystem::remove(file);
  }

  // a Tresca pair cannot be written
  {
    contact::FrictionLaw tresca;
    tresca.type       = contact::FrictionLaw::Type::tresca_isotropic;
    tresca.first      = 1e6;
    Scene       other = make_scene(tresca);
    std::string message;
    try
    {
      fclib::make_global_problem<dim>({other.body.get()},
                                      *other.contact,
                                      *other.dual,
                                      "");
    }
    catch (const ExceptionBase &e)
    {
      message = fclib::exception_message(e);
    }
    check(message.find("has Tresca or orthotropic friction") !=
            std::string::npos,
          "Tresca export refused",
          message);
  }
  return test_tools::finish();
}
