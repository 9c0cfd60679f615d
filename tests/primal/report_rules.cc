// The report's own rules as options of the primal Uzawa-CGC method
// (Kestranek & Nedoma 1996), on small 2D plane-strain scenes with
// orthogonal contact rows (a block on a rigid plane: one row per node):
//  1. release (lemma 7.2): the block's top is tilted so that the left half
//     presses and the right half lifts off.  From u = 0 on the facet of all
//     constraints, `all negative' drops every negative multiplier at once
//     and CGC ends in two outer iterations (the report's tables 11.3-11.10:
//     10 then 3 active); `one' needs one outer iteration per dropped
//     constraint more.  Both give the dual solver's displacements.
//  2. relative stopping tests (remark 7.2, subroutine CG, `CGC stopping
//     test = relative', `Uzawa stopping test = relative'): the answer agrees
//     with the dual solver's, the KKT residuals of the CGC solves are small.
//  3. per-edge friction multipliers (the report's Lambda_h, eq. 4.4): when
//     every contact edge slips the same way the nodal friction forces are
//     g w_i as with per-node multipliers, so both give the same
//     displacements; with partial slip the nodal forces stay within g w_i
//     and there is one multiplier per edge.

#include <deal.II/base/function.h>

#include <contact/contact_solver.h>
#include <contact/unit_box.h>
#include <fem/cholmod_solver.h>
#include <primal/uzawa_cgc.h>

#include <test_tools.h>

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

namespace
{
  constexpr unsigned int n_cells = 6; // per direction: 7 contact nodes

  struct Scene
  {
    std::vector<std::unique_ptr<fem::ElasticBody<2>>>  bodies;
    std::vector<const fem::ElasticBody<2> *>           pointers;
    std::unique_ptr<contact::ContactDiscretization<2>> contact;
  };

  /// the top face moved by (dx, dy0 + dy1 x)
  class TopMotion : public Function<2>
  {
  public:
    TopMotion(const double dx, const double dy0, const double dy1)
        : Function<2>(2)
        , dx(dx)
        , dy0(dy0)
        , dy1(dy1)
    {
    }
    double
    value(const Point<2> &p, const unsigned int component) const override
    {
      return component == 0 ? dx : dy0 + dy1 * p[0];
    }

  private:
    double dx, dy0, dy1;
  };

  /// block [0,1]^2 on the plane y = 0, top moved by TopMotion
  Scene
  block_on_plane(const contact::FrictionLaw &friction,
                 const double                dx,
                 const double                dy0,
                 const double                dy1)
  {
    Scene scene;
    scene.bodies.push_back(make_unit_box<2>("block", 0., n_cells, 1, 1e9));
    scene.bodies[0]->set_dirichlet_conditions(
      {{3, ComponentMask(2, true), std::make_shared<TopMotion>(dx, dy0, dy1)}});
    contact::ContactPair<2> pair;
    pair.name           = "block-plane";
    pair.slave_boundary = 2;
    pair.obstacle =
      std::make_shared<contact::PlaneObstacle<2>>(Point<2>(0., 0.),
                                                  Tensor<1, 2>({0., 1.}));
    pair.friction = friction;
    for (auto &b : scene.bodies)
    {
      b->setup();
      b->assemble();
      scene.pointers.push_back(b.get());
    }
    scene.contact = std::make_unique<contact::ContactDiscretization<2>>(
      scene.pointers, std::vector<contact::ContactPair<2>>{pair});
    return scene;
  }

  contact::FrictionLaw
  law(const contact::FrictionLaw::Type type, const double value)
  {
    contact::FrictionLaw f;
    f.type  = type;
    f.first = value;
    return f;
  }

  double
  relative_difference(const std::vector<Vector<double>> &a,
                      const std::vector<Vector<double>> &b)
  {
    double diff = 0., norm = 0.;
    for (unsigned int k = 0; k < a.size(); ++k)
    {
      Vector<double> d(a[k]);
      d -= b[k];
      diff = std::max(diff, d.linfty_norm());
      norm = std::max(norm, b[k].linfty_norm());
    }
    return diff / norm;
  }

  contact::ContactSolver<2>::Result
  dual_reference(Scene &scene)
  {
    contact::DualProblem<2> dual(
      scene.pointers,
      *scene.contact,
      [] { return std::make_unique<fem::CholmodSolver>(); });
    qp::SolverParameters qp_parameters;
    qp_parameters.solver         = "mpgp";
    qp_parameters.tolerance      = 1e-12;
    qp_parameters.max_iterations = 200000;
    contact::ContactSolver<2> solver(dual, qp_parameters, {}, {});
    auto                      result = solver.solve();
    check(result.converged, "dual reference converged", result.reason);
    return result;
  }

  primal::UzawaCGC<2>::Result
  solve_primal(Scene &scene, const primal::PrimalParameters &parameters)
  {
    primal::UzawaCGC<2> primal(scene.pointers, *scene.contact, parameters);
    return primal.solve();
  }


  void
  release_rule()
  {
    // frictionless; the top presses at x = 0 and lifts at x = 1
    auto scene = block_on_plane(
      law(contact::FrictionLaw::Type::frictionless, 0.), 0., -1e-3, 3e-3);
    const auto   reference = dual_reference(scene);
    unsigned int n_lifted  = 0;
    for (unsigned int i = 0; i < scene.contact->n_nodes(); ++i)
      n_lifted += reference.lambda(i) <= 0. ? 1 : 0;
    check(n_lifted >= 2 && n_lifted < n_cells + 1,
          "release: several, not all, nodes lift off",
          n_lifted);
    for (const std::string release : {"all negative", "one"})
    {
      primal::PrimalParameters parameters;
      parameters.cgc_release   = release;
      parameters.cgc_tolerance = 1e-12;
      const auto        result = solve_primal(scene, parameters);
      const std::string label  = "release " + release + ": ";
      check(result.converged, label + "converged", result.reason);
      const double du =
        relative_difference(result.displacements, reference.displacements);
      check(du < 1e-6, label + "displacements vs dual", du);
      const auto &outer = result.first_outer;
      check(!outer.empty() && outer[0].n_active == n_cells + 1,
            label + "starts on the facet of all constraints",
            outer.empty() ? 0 : outer[0].n_active);
      if (release == "all negative")
        check(outer.size() == 2 && outer[1].n_facet == n_cells + 1 - n_lifted,
              label + "two outer iterations, the second on the facet of "
                      "the pressed nodes (lemma 7.2), outer iterations",
              outer.size());
      else
        check(outer.size() == 1 + n_lifted,
              label + "one outer iteration per released constraint more, "
                      "outer iterations",
              outer.size());
      check(result.first_cgc.kkt.feasibility <= 1e-12 &&
              result.first_cgc.kkt.complementarity <= 1e-6,
            label + "KKT feasibility and complementarity",
            result.first_cgc.kkt.feasibility +
              result.first_cgc.kkt.complementarity);
    }
  }


  void
  relative_stopping()
  {
    // Tresca; the top moved down and sideways: part sticks, part slips
    auto scene =
      block_on_plane(law(contact::FrictionLaw::Type::tresca_isotropic, 1.5e5),
                     2e-4,
                     -1e-3,
                     0.);
    const auto reference = dual_reference(scene);
    for (const std::string preconditioner : {"none", "cholesky"})
    {
      primal::PrimalParameters parameters;
      parameters.preconditioner    = preconditioner;
      parameters.cgc_stopping      = "relative";
      parameters.cgc_tolerance     = 1e-12;
      parameters.uzawa_stopping    = "relative";
      parameters.uzawa_tolerance   = 1e-10;
      parameters.uzawa_step_factor = 1.5;
      const auto        result     = solve_primal(scene, parameters);
      const std::string label      = "relative tests, " + preconditioner + ": ";
      check(result.converged, label + "converged", result.reason);
      check(result.mu_changes.back() <= 1e-10,
            label + "last relative change of mu",
            result.mu_changes.back());
      const double du =
        relative_difference(result.displacements, reference.displacements);
      check(du < 1e-6, label + "displacements vs dual", du);
      Vector<double> dl(result.lambda);
      dl -= reference.lambda;
      const double rl = dl.linfty_norm() / reference.lambda.linfty_norm();
      check(rl < 1e-5, label + "multipliers vs dual", rl);
    }
  }


  void
  per_edge_multipliers()
  {
    const double g = 1.5e5;
    // every edge slips to the right: per edge = per node
    {
      auto scene = block_on_plane(
        law(contact::FrictionLaw::Type::tresca_isotropic, g), 5e-3, -1e-3, 0.);
      primal::PrimalParameters parameters;
      parameters.cgc_tolerance        = 1e-12;
      parameters.uzawa_tolerance      = 1e-12;
      parameters.uzawa_step_factor    = 1.5;
      const auto node                 = solve_primal(scene, parameters);
      parameters.friction_multipliers = "per edge";
      const auto edge                 = solve_primal(scene, parameters);
      check(node.converged && edge.converged,
            "all slip: per node and per edge converged",
            node.reason + " / " + edge.reason);
      check(edge.n_friction_multipliers == n_cells,
            "all slip: one multiplier per contact edge",
            edge.n_friction_multipliers);
      const double du =
        relative_difference(edge.displacements, node.displacements);
      check(du < 1e-8, "all slip: per edge = per node displacements", du);
    }
    // partial slip: nodal forces within g w_i
    {
      auto scene = block_on_plane(
        law(contact::FrictionLaw::Type::tresca_isotropic, g), 2e-4, -1e-3, 0.);
      primal::PrimalParameters parameters;
      parameters.friction_multipliers = "per edge";
      parameters.cgc_tolerance        = 1e-12;
      parameters.uzawa_tolerance      = 1e-10;
      parameters.uzawa_step_factor    = 1.5;
      const auto result               = solve_primal(scene, parameters);
      check(result.converged,
            "partial slip, per edge: converged",
            result.reason);
      const unsigned int n     = scene.contact->n_nodes();
      double             worst = 0.;
      for (unsigned int i = 0; i < n; ++i)
        worst = std::max(worst,
                         std::abs(result.lambda(n + i)) /
                           (g * scene.contact->nodes()[i].weight));
      check(worst <= 1. + 1e-12 && worst > 0.5,
            "partial slip, per edge: largest |lambda_T,i| / (g w_i)",
            worst);
    }
  }
} // namespace


int
main()
{
  release_rule();
  relative_stopping();
  per_edge_multipliers();
  return test_tools::finish();
}
