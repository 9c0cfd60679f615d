// The report's rules as options of the primal Uzawa-CGC method (lib/primal;
// Kestranek & Nedoma 1996):
//  1. `CGC release = all negative' (lemma 7.2: every constraint with a
//     negative multiplier leaves the facet at once) with the relative
//     Uzawa stopping test (remark 7.2's form) solves the same discrete
//     problem as the dual solvers: displacements to 1e-6, contact forces to
//     1e-5, for every preconditioner and version, on a block on a rigid
//     plane and on two blocks (Tresca, partial slip);
//  2. `Friction multipliers = per edge' (the report's Lambda_h, (4.4): mu
//     piecewise constant on the slave faces) satisfies the saddle-point
//     conditions of that discretization: |mu_f| <= 1 on every face, mu_f =
//     sign(s_f) on every face that slips (s_f = int_f slip ds != 0), with
//     both sticking and slipping faces present; with a slip bound so large
//     that everything sticks (|mu_f| < 1 everywhere) the mean slip of every
//     face vanishes;
//  3. bad values of the new parameters are rejected naming the parameter.

#include <deal.II/base/function.h>
#include <deal.II/base/parameter_handler.h>

#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <fem/cholmod_solver.h>
#include <primal/block_scenes.h>
#include <primal/uzawa_cgc.h>

#include <test_tools.h>

#include <iostream>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

using namespace block_scenes;

contact::FrictionLaw
tresca(const double value)
{
  return friction_law(contact::FrictionLaw::Type::tresca_isotropic, value);
}

contact::ContactSolver<2>::Result
dual_reference(Scene &scene, const std::string &name)
{
  contact::DualProblem<2> dual(scene.pointers,
                               *scene.contact,
                               [] {
                                 return std::make_unique<fem::CholmodSolver>();
                               });
  qp::SolverParameters    qp_parameters;
  qp_parameters.solver         = "mpgp";
  qp_parameters.tolerance      = 1e-12;
  qp_parameters.max_iterations = 200000;
  contact::ContactSolver<2> dual_solver(dual, qp_parameters, {}, {});
  auto                      reference = dual_solver.solve();
  check(reference.converged,
        name + ": dual solver converged",
        reference.reason);
  return reference;
}

primal::PrimalParameters
report_parameters()
{
  primal::PrimalParameters parameters;
  parameters.cgc_release         = "all negative";
  parameters.uzawa_stopping_test = "relative";
  parameters.cgc_tolerance       = 1e-12;
  parameters.uzawa_tolerance     = 1e-10;
  parameters.uzawa_step_factor   = 1.5;
  return parameters;
}

void
release_rule_vs_dual(const std::string &name, Scene &scene)
{
  const auto reference = dual_reference(scene, name);
  for (const auto &[preconditioner, version] :
       std::vector<std::pair<std::string, std::string>>{{"none", "pcg2"},
                                                        {"diagonal", "pcg2"},
                                                        {"ssor", "pcg2"},
                                                        {"ic", "pcg2"},
                                                        {"icd", "pcg2"},
                                                        {"cholesky", "pcg1"},
                                                        {"cholesky", "pcg2"}})
  {
    primal::PrimalParameters parameters = report_parameters();
    parameters.preconditioner           = preconditioner;
    parameters.version                  = version;
    primal::UzawaCGC<2> primal(scene.pointers, *scene.contact, parameters);
    const auto          result = primal.solve();
    const std::string   label =
      name + " " + preconditioner + "/" + version + ": ";
    check(result.converged,
          label + result.reason + ", Uzawa iterations",
          result.uzawa_iterations);
    const double du =
      relative_difference(result.displacements, reference.displacements);
    check(du < 1e-6, label + "displacement vs dual, relative difference", du);
    const double rl = relative_difference(result.lambda, reference.lambda);
    check(rl < 1e-5, label + "multipliers vs dual, relative difference", rl);
  }
}

// s_r = (B_T u + o_T)_r per contact node (one tangent in 2D), u the
// distributed displacements of every body
Vector<double>
nodal_slip(const Scene &scene, const std::vector<Vector<double>> &u)
{
  const auto    &c  = *scene.contact;
  const auto    &BT = c.tangential_matrix();
  Vector<double> s(c.tangential_offset());
  for (unsigned int r = 0; r < BT.m(); ++r)
    for (auto it = BT.begin(r); it != BT.end(r); ++it)
    {
      unsigned int b = 0;
      while (b + 1 < scene.pointers.size() &&
             it->column() >= c.body_offset(b + 1))
        ++b;
      s(r) += it->value() * u[b](it->column() - c.body_offset(b));
    }
  return s;
}

void
per_edge_conditions(const std::string &name, Scene &scene)
{
  primal::PrimalParameters parameters = report_parameters();
  parameters.preconditioner           = "cholesky";
  parameters.friction_multipliers     = "per edge";
  primal::UzawaCGC<2> primal(scene.pointers, *scene.contact, parameters);
  const auto          result = primal.solve();
  check(result.converged,
        name + " per edge: " + result.reason + ", Uzawa iterations",
        result.uzawa_iterations);
  const auto &faces = scene.contact->faces();
  check(result.friction_multipliers.size() == faces.size(),
        name + " per edge: one multiplier per slave face, faces",
        faces.size());
  const Vector<double> s     = nodal_slip(scene, result.displacements);
  double               s_max = 0.;
  std::vector<double>  s_face(faces.size(), 0.);
  for (unsigned int f = 0; f < faces.size(); ++f)
  {
    for (const auto &[node, w] : faces[f].nodes)
      s_face[f] += w * s(node);
    s_max = std::max(s_max, std::abs(s_face[f]));
  }
  unsigned int n_stick = 0, n_slip = 0;
  for (unsigned int f = 0; f < faces.size(); ++f)
  {
    const double mu = result.friction_multipliers(f);
    check(std::abs(mu) <= 1. + 1e-12,
          name + " per edge: |mu_f| <= 1 on face " + std::to_string(f),
          mu);
    if (std::abs(s_face[f]) > 1e-6 * s_max)
    {
      ++n_slip;
      check(std::abs(mu - (s_face[f] > 0. ? 1. : -1.)) < 1e-8,
            name + " per edge: mu_f = sign(int_f slip) on slipping face " +
              std::to_string(f) + ", mu_f",
            mu);
    }
    else
      ++n_stick;
  }
  check(n_stick > 0 && n_slip > 0,
        name + " per edge: faces stick and slip, slipping faces",
        n_slip);
}

void
per_edge_all_stick(const std::string &name, Scene &scene)
{
  primal::PrimalParameters parameters = report_parameters();
  parameters.preconditioner           = "cholesky";
  parameters.friction_multipliers     = "per edge";
  primal::UzawaCGC<2> primal(scene.pointers, *scene.contact, parameters);
  const auto          result = primal.solve();
  check(result.converged,
        name + " per edge, all stick: " + result.reason + ", Uzawa iterations",
        result.uzawa_iterations);
  check(result.friction_multipliers.linfty_norm() < 1.,
        name + " per edge, all stick: max |mu_f| < 1",
        result.friction_multipliers.linfty_norm());
  // every face sticks in the mean: int_f slip ds = 0 (the prescribed
  // sideways move is 2e-4 m over faces of 1/6 m); the nodal slips need not
  // vanish (n - 1 faces, n nodes: P0 multipliers leave one zigzag mode)
  const Vector<double> s          = nodal_slip(scene, result.displacements);
  double               s_face_max = 0.;
  for (const auto &face : scene.contact->faces())
  {
    double s_face = 0.;
    for (const auto &[node, w] : face.nodes)
      s_face += w * s(node);
    s_face_max = std::max(s_face_max, std::abs(s_face));
  }
  check(s_face_max < 1e-6 * 2e-4 / 6.,
        name + " per edge, all stick: max |int_f slip ds| [m^2]",
        s_face_max);
}


void
bad_values()
{
  for (const auto &[entry, value] :
       std::vector<std::pair<std::string, std::string>>{
         {"Uzawa stopping test", "absolute"},
         {"Friction multipliers", "per face"}})
  {
    ParameterHandler prm;
    primal::PrimalParameters::declare_parameters(prm);
    std::string message;
    try
    {
      prm.parse_input_from_string("subsection Primal solver\n  set " + entry +
                                  " = " + value + "\nend\n");
      primal::PrimalParameters p;
      p.parse_parameters(prm);
    }
    catch (const std::exception &e)
    {
      message = e.what();
    }
    check(message.find(entry) != std::string::npos,
          "`" + entry + " = " + value + "' rejected naming the parameter",
          message.find(entry) != std::string::npos ?
            message.substr(message.find(entry), entry.size()) :
            message);
  }
}

int
main()
{
  {
    auto scene = block_on_plane(tresca(1.5e5));
    release_rule_vs_dual("A (block on plane)", scene);
    per_edge_conditions("A (block on plane)", scene);
  }
  {
    auto scene = two_blocks(tresca(5e4));
    release_rule_vs_dual("B (two blocks)", scene);
    per_edge_conditions("B (two blocks)", scene);
  }
  {
    auto scene = block_on_plane(tresca(1e7));
    per_edge_all_stick("A (block on plane, g = 1e7)", scene);
  }
  bad_values();
  return test_tools::finish();
}
