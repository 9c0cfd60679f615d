// TFETI (decomposition::TFETIDual) against the undecomposed dual
// (contact::DualProblem) on the same scenes, with 1 to 16 subdomains per
// body, every QP solved tightly (1e-10):
//  A. brick (inputs/brick.prm at 4 x 8 x 4 cells): face y = 0 fixed,
//     traction on the top, gravity, orthotropic Tresca on a rigid plane;
//  B. 2D Coulomb block (8 x 8), pushed down and sideways by its top face;
//  C. 2D floating block (no Dirichlet condition), pressure and shear on
//     the top, Tresca: SMALSE-M with both duals;
//  D. 3D cantilever without contact (clamped, end traction): the dual has
//     only gluing and Dirichlet rows; against the direct solve;
//  E. 3D two bodies: a block pressed onto a fixed block (non-matching
//     meshes), frictionless, the master side cut too;
//  F. the brick at 16 subdomains, SMALSE-M with and without the coarse
//     projector P = I - G~'G~: the same answer, fewer iterations;
//  G. MPRGP with the lumped preconditioner Q B K B' Q, Q = (B B')^{-1},
//     on a beam (gluing and Dirichlet rows only) and on E's scene: the
//     same answer in fewer iterations;
//  H. the Dirichlet preconditioner Q B S B' Q: S_s v against the
//     dense Schur complement of a subdomain, and MPRGP / MPGP with it on
//     the beam and on E's scene: the same answer, fewer iterations;
//  I. hanging nodes (cells refined once in a corner): A's brick with
//     hanging nodes on the contact face, the Dirichlet face and across
//     subdomain boundaries; E's two blocks with hanging nodes on both
//     contact sides; B's Coulomb block; a quarter ring refined where it
//     touches a plane (hanging nodes on arcs, off the coarse edges), where
//     the working set leaves rows out and keeps the coarse projector;
//  J. separated rows: the brick frictionless, sheared so that part of its
//     contact face lifts; the working set drops the rows that rounds of
//     rising precision find open (their columns leave G): the same answer
//     as undecomposed and as with the rows kept, in fewer inner iterations.
//  K. the bisection partitioner: on boxes of cells (3D 4 x 8 x 4 into 16
//     parts, 2D 8 x 8 into 4) every part fills the box of its cells'
//     centres (box-shaped parts); the parts' sizes differ by at most one
//     cell (also into 6 parts, which cannot all be boxes); A's brick cut by
//     bisection into 16 subdomains gives the undecomposed answer.
//  L. gluing rows: on A's brick cut by bisection into 8 boxes (a dof
//     shared by 8 subdomains) Helmert's orthonormal rows have
//     B B' = I on the gluing rows and the chain's do not; both kinds sum
//     to zero over the copies of their dof (they span the same space) and
//     give the undecomposed answer.
//  M. the pseudoinverse: on every subdomain of A's brick in 16, K_s^+ K_s x
//     is x without its rigid-body part (x - R R'x) and K_s^+ b has no
//     rigid-body part, for x and b with all components (so F and d are
//     those of K^+, not of the fixing-dof K^#, whose F was 150 times
//     larger on the level-40 brick and 3.6e5 times on 3D Hertz).
// Checks: displacements to 1e-8 relative (largest nodal difference over
// the largest displacement), contact forces (every multiplier, relative to
// the largest) to 1e-6, the copies of every interface dof agree to 1e-8 of
// the largest displacement, G G' is the coarse problem of 6 (3D) / 3 (2D)
// modes per subdomain; the brick at 16 subdomains has a subdomain that
// touches neither a support nor the contact zone, and the contact zone is
// cut by subdomain boundaries; bad subdomain counts throw naming the
// parameter.

#include <deal.II/base/function.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <contact/contact_solver.h>
#include <contact/dual_problem.h>
#include <decomposition/cell_partition.h>
#include <decomposition/interface_schur_complement.h>
#include <decomposition/tfeti_dual.h>
#include <fem/cholmod_solver.h>

#include <test_tools.h>

#include <cmath>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

using namespace dealii;
using namespace dualcontact;

using test_tools::check;

namespace
{
  /**
   * A body of E = 2e5, nu = 0.33 on the mesh @p tria, first refined once
   * where @p refine selects a cell's centre.
   */
  template <int dim>
  std::unique_ptr<fem::ElasticBody<dim>>
  make_body_on(const std::string                               &name,
               const std::shared_ptr<Triangulation<dim>>       &tria,
               const std::vector<fem::DirichletCondition<dim>> &dirichlet,
               const std::vector<fem::TractionCondition<dim>>  &tractions,
               const std::vector<double>                       &body_force,
               const std::function<bool(const Point<dim> &)>   &refine)
  {
    if (refine)
    {
      // the cells whose centre @p refine selects, refined once: hanging
      // nodes where they meet the others
      for (const auto &cell : tria->active_cell_iterators())
        if (refine(cell->center()))
          cell->set_refine_flag();
      tria->execute_coarsening_and_refinement();
    }
    for (const auto &cell : tria->active_cell_iterators())
      cell->set_material_id(0);
    auto body = std::make_unique<fem::ElasticBody<dim>>(
      name,
      tria,
      1,
      std::map<types::material_id, fem::IsotropicMaterial>{
        {0, fem::IsotropicMaterial(2e5, 0.33)}});
    body->set_dirichlet_conditions(dirichlet);
    body->set_traction_conditions(tractions);
    if (!body_force.empty())
      body->set_body_force(
        std::make_shared<Functions::ConstantFunction<dim>>(body_force));
    body->setup();
    body->assemble();
    return body;
  }

  /** The same on a box of @p subdivisions cells (boundary ids by face). */
  template <int dim>
  std::unique_ptr<fem::ElasticBody<dim>>
  make_body(const std::string                               &name,
            const Point<dim>                                &lower,
            const Point<dim>                                &upper,
            const std::vector<unsigned int>                 &subdivisions,
            const std::vector<fem::DirichletCondition<dim>> &dirichlet,
            const std::vector<fem::TractionCondition<dim>>  &tractions,
            const std::vector<double>                       &body_force = {},
            const std::function<bool(const Point<dim> &)>   &refine     = {})
  {
    auto tria = std::make_shared<Triangulation<dim>>();
    GridGenerator::subdivided_hyper_rectangle(
      *tria, subdivisions, lower, upper, true);
    return make_body_on(name, tria, dirichlet, tractions, body_force, refine);
  }


  template <int dim>
  std::shared_ptr<Function<dim>>
  constant(const std::vector<double> &values)
  {
    return std::make_shared<Functions::ConstantFunction<dim>>(values);
  }

  template <int dim>
  ComponentMask
  mask(const std::vector<unsigned int> &components)
  {
    ComponentMask m(dim, false);
    for (const unsigned int c : components)
      m.set(c, true);
    return m;
  }

  std::function<std::unique_ptr<fem::StiffnessSolver>()>
  cholmod()
  {
    return [] { return std::make_unique<fem::CholmodSolver>(); };
  }

  template <int dim>
  typename contact::ContactSolver<dim>::Result
  solve(contact::DualFormulation<dim>       &dual,
        const std::string                   &solver,
        const double                         tolerance = 1e-10,
        const qp::SMALSEMParameters         &smalse = qp::SMALSEMParameters(),
        const std::string                   &preconditioner = "none",
        const contact::WorkingSetParameters &working_set =
          contact::WorkingSetParameters())
  {
    qp::SolverParameters parameters;
    parameters.solver         = solver;
    parameters.preconditioner = preconditioner;
    parameters.tolerance      = tolerance;
    parameters.max_iterations = 20000;
    contact::CoulombParameters coulomb;
    coulomb.tolerance = 1e-10;
    contact::ContactSolver<dim> contact_solver(
      dual, parameters, smalse, coulomb, working_set);
    return contact_solver.solve();
  }

  /** QP iterations summed over the QPs of a contact solve. */
  template <int dim>
  unsigned int
  inner_iterations(const typename contact::ContactSolver<dim>::Result &result)
  {
    unsigned int n = 0;
    for (const auto &s : result.qp_statistics)
      n += s.iterations;
    return n;
  }

  /** Largest difference over the largest value, over all bodies. */
  double
  relative_difference(const std::vector<Vector<double>> &a,
                      const std::vector<Vector<double>> &b)
  {
    double difference = 0, size = 0;
    for (unsigned int k = 0; k < a.size(); ++k)
    {
      Vector<double> d = a[k];
      d -= b[k];
      difference = std::max(difference, d.linfty_norm());
      size       = std::max(size, b[k].linfty_norm());
    }
    return difference / size;
  }

  /**
   * The scene of @p bodies and @p pairs solved undecomposed and with TFETI
   * at each of @p counts subdomains per body.
   */
  template <int dim>
  void
  compare(const std::string                                &name,
          const std::vector<const fem::ElasticBody<dim> *> &bodies,
          const std::vector<contact::ContactPair<dim>>     &pairs,
          const std::vector<unsigned int>                  &counts,
          const std::string                                &solver,
          const std::function<void(const decomposition::TFETIDual<dim> &)>
                                              &inspect = {},
          const contact::WorkingSetParameters &working_set =
            contact::WorkingSetParameters(),
          const decomposition::DecompositionParameters &base =
            decomposition::DecompositionParameters())
  {
    std::cout << name << std::endl;
    const contact::ContactDiscretization<dim>    contact(bodies, pairs);
    typename contact::ContactSolver<dim>::Result reference;
    unsigned int                                 n_contact = 0;
    if (pairs.empty())
    {
      // no contact: the direct solve of every body
      for (const auto *body : bodies)
      {
        fem::CholmodSolver direct;
        reference.displacements.emplace_back();
        body->solve(direct, reference.displacements.back());
      }
    }
    else
    {
      contact::DualProblem<dim> undecomposed(bodies, contact, cholmod());
      reference = solve(undecomposed, solver);
      check(reference.converged, "undecomposed: " + reference.reason, "");
      n_contact = undecomposed.n_multipliers();
    }
    double largest = 0;
    for (unsigned int r = 0; r < n_contact; ++r)
      largest = std::max(largest, std::abs(reference.lambda(r)));

    for (const unsigned int count : counts)
    {
      decomposition::DecompositionParameters parameters = base;
      parameters.subdomains_per_body                    = {count};
      decomposition::TFETIDual<dim> tfeti(bodies,
                                          contact,
                                          parameters,
                                          cholmod());
      const auto                    result = solve(
        tfeti, solver, 1e-10, qp::SMALSEMParameters(), "none", working_set);
      const std::string label =
        "  " + std::to_string(tfeti.n_subdomains()) + " subdomains (" +
        std::to_string(tfeti.n_gluing_multipliers()) + " gluing, " +
        std::to_string(tfeti.n_dirichlet_multipliers()) + " Dirichlet, " +
        std::to_string(tfeti.n_contact_multipliers()) + " contact): ";
      check(result.converged,
            label + result.reason + " (" + result.qp_statistics.back().message +
              "), QP iterations",
            result.qp_statistics.back().iterations);
      check(tfeti.n_subdomains() >= count * bodies.size() &&
              tfeti.n_rigid_body_modes() ==
                tfeti.n_subdomains() * dim * (dim + 1) / 2,
            label + "coarse problem size",
            tfeti.n_rigid_body_modes());
      check(tfeti.n_contact_multipliers() == n_contact,
            label + "contact multipliers as undecomposed",
            tfeti.n_contact_multipliers());
      const double displacement =
        relative_difference(result.displacements, reference.displacements);
      check(displacement < 1e-8,
            label + "displacements against undecomposed",
            displacement);
      double force = 0;
      for (unsigned int r = 0; r < n_contact; ++r)
        force =
          std::max(force, std::abs(result.lambda(r) - reference.lambda(r)));
      if (n_contact > 0)
        check(force <= 1e-6 * largest,
              label + "contact multipliers against undecomposed",
              force / largest);
      check(tfeti.relative_interface_jump() < 1e-8,
            label + "largest jump between copies / largest |u|",
            tfeti.relative_interface_jump());
      if (inspect)
        inspect(tfeti);
    }
  }


  /**
   * A frictionless pair of @p slave_boundary on the rigid plane through the
   * origin whose outward normal is the last axis (z = 0 in 3D, y = 0 in
   * 2D).
   */
  template <int dim>
  contact::ContactPair<dim>
  pair_on_plane(const std::string &name, const unsigned int slave_boundary)
  {
    Point<dim> normal;
    normal[dim - 1] = 1;
    contact::ContactPair<dim> pair;
    pair.name           = name;
    pair.slave_boundary = slave_boundary;
    pair.obstacle =
      std::make_shared<contact::PlaneObstacle<dim>>(Point<dim>(), normal);
    return pair;
  }


  /** The brick of inputs/brick.prm, 4 x 8 x 4 cells. */
  std::unique_ptr<fem::ElasticBody<3>>
  brick_body()
  {
    return make_body<3>("brick",
                        Point<3>(0, 0, 0),
                        Point<3>(1, 2, 1),
                        {4, 8, 4},
                        {{2, mask<3>({0, 1, 2}), constant<3>({0, 0, 0})}},
                        {{5, constant<3>({150, 300, 0})}},
                        {0, 0, -9.81 * 7.85e-2});
  }

  /** Its orthotropic Tresca contact with the plane z = 0. */
  contact::ContactPair<3>
  brick_pair()
  {
    contact::ContactPair<3> pair = pair_on_plane<3>("brick-plane", 4);
    pair.friction.type   = contact::FrictionLaw::Type::tresca_orthotropic;
    pair.friction.first  = 10;
    pair.friction.second = 5;
    pair.first_tangent_direction = Point<3>(1, 0, 0);
    pair.search_distance         = 0.01;
    return pair;
  }


  /** A. The brick of inputs/brick.prm, 4 x 8 x 4. */
  void
  brick()
  {
    const auto                    body = brick_body();
    const contact::ContactPair<3> pair = brick_pair();

    // which subdomains touch a support / the contact zone, and whether a
    // contact dof has copies in two subdomains
    const auto inspect = [&](const decomposition::TFETIDual<3> &tfeti)
    {
      if (tfeti.n_subdomains() < 16)
        return;
      std::set<types::global_dof_index>       contact_dofs;
      const contact::ContactDiscretization<3> contact({body.get()}, {pair});
      const auto                             &B = contact.normal_matrix();
      for (unsigned int r = 0; r < B.m(); ++r)
        for (auto it = B.begin(r); it != B.end(r); ++it)
          contact_dofs.insert(it->column());
      unsigned int                                    n_isolated = 0;
      std::map<types::global_dof_index, unsigned int> copies;
      for (unsigned int s = 0; s < tfeti.n_subdomains(); ++s)
      {
        bool supported = false, in_contact = false;
        for (const auto dof : tfeti.subdomain(s).dofs())
        {
          supported |= body->constraints().is_constrained(dof);
          in_contact |= contact_dofs.count(dof) > 0;
          if (contact_dofs.count(dof) > 0)
            ++copies[dof];
        }
        n_isolated += !supported && !in_contact;
      }
      unsigned int n_shared = 0;
      for (const auto &[dof, n] : copies)
        n_shared += n > 1;
      check(n_isolated > 0,
            "  subdomains touching neither support nor contact",
            n_isolated);
      check(n_shared > 0,
            "  contact dofs with copies in two subdomains",
            n_shared);
    };
    compare<3>("A. brick 4 x 8 x 4, orthotropic Tresca",
               {body.get()},
               {pair},
               {2, 16},
               "auto",
               inspect);
  }


  /** Coulomb friction (mu = 0.3) of a 2D block's bottom on the plane y = 0. */
  contact::ContactPair<2>
  coulomb_pair()
  {
    contact::ContactPair<2> pair = pair_on_plane<2>("block-plane", 2);
    pair.friction.type  = contact::FrictionLaw::Type::coulomb_isotropic;
    pair.friction.first = 0.3;
    return pair;
  }


  /** B. 2D Coulomb block pushed down and sideways. */
  void
  coulomb_block()
  {
    const auto body =
      make_body<2>("block",
                   Point<2>(0, 0),
                   Point<2>(1, 1),
                   {8, 8},
                   {{3, mask<2>({0, 1}), constant<2>({2e-3, -1e-3})}},
                   {});
    compare<2>("B. 2D Coulomb block",
               {body.get()},
               {coulomb_pair()},
               {1, 3, 7},
               "mprgp");
  }


  /** C. 2D floating block: contact holds it. */
  void
  floating_block()
  {
    const auto              body = make_body<2>("floating block",
                                   Point<2>(0, 0),
                                   Point<2>(1, 1),
                                   {8, 8},
                                   {},
                                   {{3, constant<2>({1e-2, -1})}});
    contact::ContactPair<2> pair = pair_on_plane<2>("block-plane", 2);
    pair.friction.type           = contact::FrictionLaw::Type::tresca_isotropic;
    pair.friction.first          = 0.1;
    compare<2>(
      "C. 2D floating block, Tresca", {body.get()}, {pair}, {1, 4}, "mprgp");
  }


  /** D. 3D cantilever, no contact: against the direct solve too. */
  void
  cantilever()
  {
    const auto body =
      make_body<3>("cantilever",
                   Point<3>(0, 0, 0),
                   Point<3>(4, 1, 1),
                   {8, 2, 2},
                   {{0, mask<3>({0, 1, 2}), constant<3>({0, 0, 0})}},
                   {{1, constant<3>({0, 0, -100})}});
    compare<3>(
      "D. 3D cantilever, no contact", {body.get()}, {}, {1, 5, 16}, "mprgp");
  }


  /** The fixed lower block of E and G, @p n x @p n x @p n cells. */
  std::unique_ptr<fem::ElasticBody<3>>
  lower_block(const unsigned int n)
  {
    return make_body<3>("lower block",
                        Point<3>(0, 0, -1),
                        Point<3>(1, 1, 0),
                        {n, n, n},
                        {{4, mask<3>({0, 1, 2}), constant<3>({0, 0, 0})}},
                        {});
  }

  /** The upper block of E and G, pressed down and pushed sideways. */
  std::unique_ptr<fem::ElasticBody<3>>
  upper_block()
  {
    return make_body<3>(
      "upper block",
      Point<3>(0.1, 0.1, 0),
      Point<3>(0.9, 0.9, 0.6),
      {4, 4, 3},
      {{5, mask<3>({0, 1, 2}), constant<3>({1e-4, 0, -1e-3})}},
      {});
  }

  /** Frictionless contact of the upper block's bottom on the lower one. */
  contact::ContactPair<3>
  block_pair()
  {
    contact::ContactPair<3> pair;
    pair.name            = "upper-lower";
    pair.slave_body      = 1;
    pair.slave_boundary  = 4;
    pair.master_body     = 0;
    pair.master_boundary = 5;
    return pair;
  }


  /** E. 3D: a block pressed onto a fixed block, both cut. */
  void
  two_blocks()
  {
    const auto lower = lower_block(3);
    const auto upper = upper_block();
    compare<3>("E. 3D block on block, frictionless",
               {lower.get(), upper.get()},
               {block_pair()},
               {1, 3},
               "mprgp");
  }


  /**
   * F. SMALSE-M on the brick at 16 subdomains with the coarse projector
   * (inner Hessian P F P + rho G~'G~) and without (F + 10 lambda_max
   * G~'G~): the same answer, and the projector needs far fewer inner
   * iterations (on the thesis-size brick 3.6 to 7.6 times fewer,
   * doc/benchmarks/tfeti.md).
   */
  void
  coarse_projector()
  {
    std::cout << "F. brick, 16 subdomains: SMALSE-M with and without the "
                 "coarse projector"
              << std::endl;
    const auto                              body = brick_body();
    const contact::ContactPair<3>           pair = brick_pair();
    const contact::ContactDiscretization<3> contact({body.get()}, {pair});
    decomposition::DecompositionParameters  parameters;
    parameters.subdomains_per_body = {16};
    decomposition::TFETIDual<3>                    tfeti({body.get()},
                                      contact,
                                      parameters,
                                      cholmod());
    std::vector<contact::ContactSolver<3>::Result> results;
    std::vector<unsigned int>                      iterations;
    for (const bool projector : {true, false})
    {
      qp::SMALSEMParameters smalse;
      smalse.coarse_projector = projector;
      results.push_back(solve(tfeti, "mpgp", 1e-6, smalse));
      const unsigned int n = inner_iterations<3>(results.back());
      iterations.push_back(n);
      check(results.back().converged,
            std::string(projector ? "  with" : "  without") +
              " the projector: " + results.back().reason + ", inner iterations",
            n);
    }
    // 336 against 546 with the pseudoinverses K_s^+ (with the fixing-dof
    // K_s^#, whose F is far larger off the kernel of G, the penalty form
    // needed 2 to 8 times the projector's)
    check(4 * iterations[0] <= 3 * iterations[1],
          "  the projector saves at least a quarter of the inner iterations",
          std::to_string(iterations[0]) + " against " +
            std::to_string(iterations[1]));
    const double difference =
      relative_difference(results[0].displacements, results[1].displacements);
    check(difference < 1e-5,
          "  displacements with and without the projector",
          difference);
  }


  /** The clamped 3D beam of G and H: 16 x 4 x 4 cells, end traction. */
  std::unique_ptr<fem::ElasticBody<3>>
  clamped_beam()
  {
    return make_body<3>("beam",
                        Point<3>(0, 0, 0),
                        Point<3>(4, 1, 1),
                        {16, 4, 4},
                        {{0, mask<3>({0, 1, 2}), constant<3>({0, 0, 0})}},
                        {{1, constant<3>({0, 0, -100})}});
  }


  /**
   * Each of @p solvers (inside SMALSE-M with the coarse projector) with
   * `Preconditioner = @p preconditioner' against none on the beam (16
   * subdomains) and on E's frictionless block on block (4 per body):
   * converged, fewer inner iterations with it, the same displacements.
   */
  void
  compare_preconditioner(const std::string              &preconditioner,
                         const std::vector<std::string> &solvers)
  {
    const auto beam  = clamped_beam();
    const auto lower = lower_block(4);
    const auto upper = upper_block();
    const auto pair  = block_pair();
    for (const auto &[name, bodies, pairs, count] :
         std::vector<std::tuple<std::string,
                                std::vector<const fem::ElasticBody<3> *>,
                                std::vector<contact::ContactPair<3>>,
                                unsigned int>>{
           {"beam, 16 subdomains", {beam.get()}, {}, 16},
           {"block on block, 4 subdomains per body",
            {lower.get(), upper.get()},
            {pair},
            4}})
    {
      const contact::ContactDiscretization<3> contact(bodies, pairs);
      decomposition::DecompositionParameters  parameters;
      parameters.subdomains_per_body = {count};
      parameters.preconditioner      = preconditioner;
      decomposition::TFETIDual<3> tfeti(bodies, contact, parameters, cholmod());
      for (const std::string &solver : solvers)
      {
        std::vector<contact::ContactSolver<3>::Result> results;
        std::vector<unsigned int>                      iterations;
        for (const std::string &used : {preconditioner, std::string("none")})
        {
          results.push_back(
            solve(tfeti, solver, 1e-8, qp::SMALSEMParameters(), used));
          iterations.push_back(inner_iterations<3>(results.back()));
          check(results.back().converged,
                "  " + name + ", " + solver + ", Preconditioner = " + used +
                  ": " + results.back().reason + " (" +
                  results.back().qp_statistics.back().message +
                  "), inner iterations",
                iterations.back());
        }
        check(iterations[0] < iterations[1],
              "  " + name + ", " + solver + ": fewer inner iterations with it",
              std::to_string(iterations[0]) + " against " +
                std::to_string(iterations[1]));
        const double difference = relative_difference(results[0].displacements,
                                                      results[1].displacements);
        check(difference < 1e-6,
              "  " + name + ", " + solver +
                ": displacements with and without it",
              difference);
      }
    }
  }


  /**
   * G. The lumped preconditioner Q B K B' Q in MPRGP (compare_preconditioner).
   * Both runs also check the projector's outer loop on a problem without
   * inequalities: from the infeasible start it spent 90 outer iterations
   * without inner work before SMALSE-M tightened M there (the beam
   * without the preconditioner hit the 100-outer limit).  Unscaled (B K B'
   * without Q = (B B')^{-1}) it cost iterations here: 162 against 93 and
   * 97 against 69; scaled 38 and 22.
   */
  void
  lumped_preconditioner()
  {
    std::cout << "G. MPRGP with and without the lumped preconditioner"
              << std::endl;
    compare_preconditioner("lumped", {"mprgp"});
  }


  /**
   * H. The Dirichlet preconditioner.  First InterfaceSchurComplement
   * against the dense S = K_bb - K_bi K_ii^{-1} K_ib of a beam subdomain
   * (an interface of scattered dofs, every fourth); then MPRGP and MPGP
   * with Preconditioner = dirichlet against none (compare_preconditioner).
   */
  void
  dirichlet_preconditioner()
  {
    std::cout << "H. the Dirichlet preconditioner" << std::endl;
    const auto beam = clamped_beam();
    {
      const contact::ContactDiscretization<3> contact({beam.get()}, {});
      decomposition::DecompositionParameters  parameters;
      parameters.subdomains_per_body = {16};
      // (with a preconditioner that applies K_s, so that K_s is kept)
      parameters.preconditioner = "dirichlet";
      decomposition::TFETIDual<3> tfeti({beam.get()},
                                        contact,
                                        parameters,
                                        cholmod());
      const SparseMatrix<double> &K = tfeti.subdomain(0).stiffness_matrix();
      const unsigned int          n = K.m();
      std::vector<unsigned int>   interface, interior;
      for (unsigned int i = 0; i < n; ++i)
        (i % 4 == 0 ? interface : interior).push_back(i);
      const decomposition::InterfaceSchurComplement schur(
        K, interface, std::make_unique<fem::CholmodSolver>(), "subdomain 0");
      FullMatrix<double> Kii(interior.size()),
        Kib(interior.size(), interface.size());
      FullMatrix<double> S(interface.size());
      for (unsigned int r = 0; r < interior.size(); ++r)
      {
        for (unsigned int c = 0; c < interior.size(); ++c)
          Kii(r, c) = K.el(interior[r], interior[c]);
        for (unsigned int c = 0; c < interface.size(); ++c)
          Kib(r, c) = K.el(interior[r], interface[c]);
      }
      for (unsigned int r = 0; r < interface.size(); ++r)
        for (unsigned int c = 0; c < interface.size(); ++c)
          S(r, c) = K.el(interface[r], interface[c]);
      Kii.gauss_jordan();
      FullMatrix<double> X(interior.size(), interface.size());
      Kii.mmult(X, Kib);
      FullMatrix<double> KbiX(interface.size()); // K_bi K_ii^{-1} K_ib
      Kib.Tmmult(KbiX, X);
      S.add(-1., KbiX);
      Vector<double> v(n), y;
      for (unsigned int i = 0; i < n; ++i)
        v(i) = std::sin(1. + 3. * i);
      schur.vmult(y, v);
      Vector<double> vb(interface.size()), Sv(interface.size());
      for (unsigned int k = 0; k < interface.size(); ++k)
        vb(k) = v(interface[k]);
      S.vmult(Sv, vb);
      double error = 0, interior_value = 0;
      for (unsigned int k = 0; k < interface.size(); ++k)
        error = std::max(error, std::abs(y(interface[k]) - Sv(k)));
      for (const unsigned int i : interior)
        interior_value = std::max(interior_value, std::abs(y(i)));
      check(error <= 1e-10 * Sv.linfty_norm() && interior_value == 0.,
            "  S v against the dense Schur complement (relative), "
            "zero on the interior",
            error / Sv.linfty_norm());
    }

    compare_preconditioner("dirichlet", {"mprgp", "mpgp"});
  }


  /** Too many subdomains: the error names the parameter. */
  void
  bad_counts()
  {
    const auto                              body = make_body<2>("Body 1",
                                   Point<2>(0, 0),
                                   Point<2>(1, 1),
                                   {2, 2},
                                   {{0, mask<2>({0, 1}), constant<2>({0, 0})}},
                                   {{1, constant<2>({0, -1})}});
    const contact::ContactDiscretization<2> contact({body.get()}, {});
    decomposition::DecompositionParameters  parameters;
    parameters.subdomains_per_body = {5};
    std::string message;
    try
    {
      decomposition::TFETIDual<2> tfeti({body.get()},
                                        contact,
                                        parameters,
                                        cholmod());
    }
    catch (const std::exception &e)
    {
      // deal.II wraps the message's lines: compare word by word
      std::istringstream words(e.what());
      for (std::string word; words >> word;)
        message += word + " ";
    }
    check(message.find("`Subdomains per body' in `subsection "
                       "Decomposition' asks for 5 subdomains of Body 1, "
                       "which has only 4 cells") != std::string::npos,
          "5 subdomains of 4 cells: error names the parameter",
          message.empty() ? "no error" : "thrown");
  }


  /**
   * I. Hanging nodes: every scene refined once in part, so that refined
   * and coarse cells meet on the contact faces, on the Dirichlet faces and
   * across subdomain boundaries.  TFETI glues a hanging dof to its parents
   * by a multiplier row.
   */
  void
  hanging_nodes()
  {
    // the gluing rows: a chain through the copies of every dof that is
    // not prescribed, and one row per hanging dof
    const auto one_row_per_hanging_dof = [](const fem::ElasticBody<3> &body)
    {
      return [&body](const decomposition::TFETIDual<3> &tfeti)
      {
        std::vector<unsigned int> copies(body.n_dofs(), 0);
        for (unsigned int s = 0; s < tfeti.n_subdomains(); ++s)
          for (const auto dof : tfeti.subdomain(s).dofs())
            ++copies[dof];
        const auto  &hanging  = body.hanging_node_constraints();
        unsigned int expected = hanging.n_constraints();
        for (unsigned int i = 0; i < body.n_dofs(); ++i)
          if (!body.constraints().is_constrained(i) ||
              hanging.is_constrained(i))
            expected += copies[i] - 1;
        check(tfeti.n_gluing_multipliers() == expected,
              "  gluing rows: copies - 1 per free dof, one per hanging dof",
              tfeti.n_gluing_multipliers());
      };
    };

    const auto brick =
      make_body<3>("brick, refined corner",
                   Point<3>(0, 0, 0),
                   Point<3>(1, 2, 1),
                   {4, 8, 4},
                   {{2, mask<3>({0, 1, 2}), constant<3>({0, 0, 0})}},
                   {{5, constant<3>({150, 300, 0})}},
                   {0, 0, -9.81 * 7.85e-2},
                   [](const Point<3> &p)
                   { return p[0] < 0.5 && p[1] < 1.0 && p[2] < 0.5; });
    check(brick->triangulation().has_hanging_nodes() &&
            brick->hanging_node_constraints().n_constraints() > 0,
          "I. brick: hanging-node constraints",
          brick->hanging_node_constraints().n_constraints());
    compare<3>("I. brick 4 x 8 x 4 with a refined corner, orthotropic Tresca",
               {brick.get()},
               {brick_pair()},
               {1, 3, 8},
               "auto",
               one_row_per_hanging_dof(*brick));

    const auto lower =
      make_body<3>("lower block, refined corner",
                   Point<3>(0, 0, -1),
                   Point<3>(1, 1, 0),
                   {3, 3, 3},
                   {{4, mask<3>({0, 1, 2}), constant<3>({0, 0, 0})}},
                   {},
                   {},
                   [](const Point<3> &p) { return p[0] > 0.5 && p[2] > -0.5; });
    const auto upper =
      make_body<3>("upper block, refined corner",
                   Point<3>(0.1, 0.1, 0),
                   Point<3>(0.9, 0.9, 0.6),
                   {4, 4, 3},
                   {{5, mask<3>({0, 1, 2}), constant<3>({1e-4, 0, -1e-3})}},
                   {},
                   {},
                   [](const Point<3> &p) { return p[1] < 0.5 && p[2] < 0.2; });
    compare<3>("I. 3D block on block, both contact sides refined in part",
               {lower.get(), upper.get()},
               {block_pair()},
               {1, 4},
               "mprgp");

    const auto block =
      make_body<2>("block, refined corner",
                   Point<2>(0, 0),
                   Point<2>(1, 1),
                   {8, 8},
                   {{3, mask<2>({0, 1}), constant<2>({2e-3, -1e-3})}},
                   {},
                   {},
                   [](const Point<2> &p) { return p[0] < 0.5 || p[1] > 0.7; });
    compare<2>("I. 2D Coulomb block, refined in part",
               {block.get()},
               {coulomb_pair()},
               {1, 3, 7},
               "mprgp");

    // a quarter ring (centre (0, 1), radii 0.5 and 1, x >= 0, y <= 1)
    // pressed onto the plane y = 0, refined near its lowest point; every
    // cell and face is on the circles' manifold, so refined vertices lie
    // on arcs, off the coarse edges: the rigid rotations are then no exact
    // zero-energy modes of a field with hanging nodes condensed (the first
    // version condensed them inside the subdomains and missed the 3D
    // Hertz energy by 1e-4; as rows, the cells keep their own vertices)
    auto ring = std::make_shared<Triangulation<2>>();
    GridGenerator::quarter_hyper_shell(*ring, Point<2>(), 0.5, 1., 4);
    GridTools::rotate(-numbers::PI / 2, *ring);
    GridTools::shift(Point<2>(0, 1), *ring);
    ring->set_all_manifold_ids(0);
    ring->set_manifold(0, SphericalManifold<2>(Point<2>(0, 1)));
    for (const auto &cell : ring->active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
        {
          const Point<2> c = cell->face(f)->center();
          cell->face(f)->set_boundary_id(std::abs(c[0]) < 1e-10            ? 1 :
                                         std::abs(c[1] - 1) < 1e-10        ? 2 :
                                         c.distance(Point<2>(0, 1)) > 0.75 ? 0 :
                                                                             3);
        }
    ring->refine_global(1);
    const auto quarter_ring =
      make_body_on<2>("quarter ring, refined near its lowest point",
                      ring,
                      {{1, mask<2>({0}), constant<2>({0, 0})},
                       {2, mask<2>({0, 1}), constant<2>({0, -2e-3})}},
                      {},
                      {},
                      [](const Point<2> &p)
                      { return p.distance(Point<2>(0, 0)) < 0.4; });
    check(quarter_ring->hanging_node_constraints().n_constraints() > 0,
          "I. quarter ring: hanging-node constraints",
          quarter_ring->hanging_node_constraints().n_constraints());
    contact::ContactPair<2> ring_pair = pair_on_plane<2>("ring-plane", 0);
    ring_pair.search_distance         = 0.5;
    compare<2>("I. 2D quarter ring on a plane, refined where it touches",
               {quarter_ring.get()},
               {ring_pair},
               {1, 4},
               "mprgp");

    // the working set leaves out the rows beyond its reach, and the QP on
    // the rest keeps SMALSE-M's coarse projector (its columns of G~ made
    // orthonormal again)
    {
      const contact::ContactDiscretization<2> contact({quarter_ring.get()},
                                                      {ring_pair});
      decomposition::DecompositionParameters  parameters;
      parameters.subdomains_per_body = {4};
      decomposition::TFETIDual<2> tfeti({quarter_ring.get()},
                                        contact,
                                        parameters,
                                        cholmod());
      const auto                  result  = solve(tfeti, "mprgp");
      const auto                 &message = result.qp_statistics.back().message;
      unsigned int                n_dropped = 0;
      for (const auto &record : result.working_sets)
        n_dropped += record.n_dropped;
      check(n_dropped > 0 &&
              message.find("coarse projector") != std::string::npos,
            "  working set: rows left out, coarse projector kept (" + message +
              "), rows left out",
            n_dropped);
    }
  }

  /**
   * J. Separated rows: A's brick without friction, so that the shear of
   * its top face lifts part of the contact face, with `Drop separated
   * rows': against the undecomposed dual; then every row kept at first
   * (reach factor 1e6) and the rows the rounds find open dropped, or all
   * kept: the same answer, and fewer inner iterations with them dropped.
   */
  void
  separated_rows()
  {
    const auto              body = brick_body();
    contact::ContactPair<3> pair = pair_on_plane<3>("brick-plane", 4);
    pair.search_distance         = 0.01;
    contact::WorkingSetParameters drop;
    drop.drop_separated_rows = true;
    compare<3>("J. brick 4 x 8 x 4, frictionless: separated rows dropped",
               {body.get()},
               {pair},
               {4, 16},
               "mprgp",
               {},
               drop);

    const contact::ContactDiscretization<3> contact({body.get()}, {pair});
    decomposition::DecompositionParameters  parameters;
    parameters.subdomains_per_body = {16};
    std::vector<typename contact::ContactSolver<3>::Result> results;
    std::vector<unsigned int>                               separated;
    for (const bool drop : {false, true})
    {
      decomposition::TFETIDual<3>   tfeti({body.get()},
                                        contact,
                                        parameters,
                                        cholmod());
      contact::WorkingSetParameters working_set;
      working_set.reach_factor        = 1e6;
      working_set.drop_separated_rows = drop;
      results.push_back(solve(
        tfeti, "mprgp", 1e-10, qp::SMALSEMParameters(), "none", working_set));
      check(results.back().converged,
            "  J. converged: " + results.back().reason,
            inner_iterations<3>(results.back()));
      separated.push_back(results.back().working_sets.back().n_separated);
    }
    check(separated[0] == 0 && separated[1] > 0,
          "  J. rows dropped as separated (kept / dropped)",
          separated[1]);
    check(relative_difference(results[1].displacements,
                              results[0].displacements) < 1e-8,
          "  J. displacements, rows dropped against kept",
          relative_difference(results[1].displacements,
                              results[0].displacements));
    const unsigned int kept    = inner_iterations<3>(results[0]);
    const unsigned int dropped = inner_iterations<3>(results[1]);
    std::cout << "  J. inner iterations: rows kept " << kept
              << ", separated rows dropped " << dropped << std::endl;
    check(dropped < kept,
          "  J. fewer inner iterations with the separated rows dropped",
          dropped);
  }


  /**
   * K. bisect_cells() on the box @p lower - @p upper of @p subdivisions
   * cells into @p n_parts parts: the sizes differ by at most one cell,
   * and, if @p boxes, every part fills the box spanned by its cells'
   * centres.
   */
  template <int dim>
  void
  bisection_parts(const std::vector<unsigned int> &subdivisions,
                  const Point<dim>                &upper,
                  const unsigned int               n_parts,
                  const bool                       boxes)
  {
    Triangulation<dim> triangulation;
    GridGenerator::subdivided_hyper_rectangle(triangulation,
                                              subdivisions,
                                              Point<dim>(),
                                              upper);
    const std::vector<unsigned int> part =
      decomposition::bisect_cells(triangulation, n_parts);
    std::vector<Point<dim>>   low(n_parts), high(n_parts);
    std::vector<unsigned int> size(n_parts, 0);
    for (const auto &cell : triangulation.active_cell_iterators())
    {
      const unsigned int p = part[cell->active_cell_index()];
      const Point<dim>   c = cell->center();
      if (size[p]++ == 0)
        low[p] = high[p] = c;
      for (unsigned int d = 0; d < dim; ++d)
      {
        low[p][d]  = std::min(low[p][d], c[d]);
        high[p][d] = std::max(high[p][d], c[d]);
      }
    }
    unsigned int n_not_boxes = 0;
    for (unsigned int p = 0; p < n_parts; ++p)
    {
      unsigned int in_box = 1;
      for (unsigned int d = 0; d < dim; ++d)
        in_box *= static_cast<unsigned int>(std::round(
                    (high[p][d] - low[p][d]) / (upper[d] / subdivisions[d]))) +
                  1;
      n_not_boxes += in_box != size[p];
    }
    const std::string label = "  K. " + std::to_string(dim) + "D box into " +
                              std::to_string(n_parts) + " parts: ";
    if (boxes)
      check(n_not_boxes == 0, label + "parts that are not boxes", n_not_boxes);
    const auto [smallest, largest] =
      std::minmax_element(size.begin(), size.end());
    check(*smallest > 0 && *largest - *smallest <= 1,
          label + "largest minus smallest part [cells]",
          *largest - *smallest);
  }


  void
  bisection()
  {
    std::cout << "K. bisection partitioner" << std::endl;
    bisection_parts<3>({4, 8, 4}, Point<3>(1, 2, 1), 16, true);
    bisection_parts<3>({4, 8, 4}, Point<3>(1, 2, 1), 6, false);
    bisection_parts<2>({8, 8}, Point<2>(1, 1), 4, true);
    const auto                             body = brick_body();
    decomposition::DecompositionParameters parameters;
    parameters.partitioner =
      decomposition::DecompositionParameters::Partitioner::bisection;
    compare<3>("K. brick 4 x 8 x 4 cut by bisection",
               {body.get()},
               {brick_pair()},
               {16},
               "auto",
               {},
               contact::WorkingSetParameters(),
               parameters);
  }


  /**
   * The largest |(B B')_rs - delta_rs| over the gluing rows r, s of
   * @p tfeti (one process: every subdomain's entries are here), and the
   * largest |sum of a gluing row's entries| (zero: each row is orthogonal to
   * the glued motion of its dof's copies, which all have value 1 there).
   */
  std::pair<double, double>
  gluing_gram_defect(const decomposition::TFETIDual<3> &tfeti)
  {
    const auto        &rows  = tfeti.constraint_rows();
    const unsigned int first = tfeti.n_contact_multipliers();
    const unsigned int last  = first + tfeti.n_gluing_multipliers();
    // per (subdomain, local dof): the gluing rows through it and their values
    std::map<std::pair<unsigned int, unsigned int>,
             std::vector<std::pair<unsigned int, double>>>
                        columns;
    std::vector<double> row_sum(rows.n_rows(), 0.);
    for (unsigned int s = 0; s < tfeti.n_subdomains(); ++s)
      for (const auto &entry : rows.entries(s))
        if (entry.row >= first && entry.row < last)
        {
          columns[{s, entry.local}].push_back({entry.row, entry.value});
          row_sum[entry.row] += entry.value;
        }
    std::map<std::pair<unsigned int, unsigned int>, double> gram;
    for (const auto &[column, entries] : columns)
      for (const auto &[r, a] : entries)
        for (const auto &[t, b] : entries)
          gram[{r, t}] += a * b;
    double defect = 0., sum = 0.;
    for (unsigned int r = first; r < last; ++r)
    {
      sum    = std::max(sum, std::abs(row_sum[r]));
      defect = std::max(defect, std::abs(gram[{r, r}] - 1.));
    }
    for (const auto &[rt, value] : gram)
      if (rt.first != rt.second)
        defect = std::max(defect, std::abs(value));
    return {defect, sum};
  }


  /** L. Chain and orthonormal gluing rows. */
  void
  gluing_rows()
  {
    std::cout << "L. gluing rows" << std::endl;
    using Gluing    = decomposition::DecompositionParameters::Gluing;
    const auto body = brick_body();
    for (const Gluing gluing : {Gluing::chain, Gluing::orthonormal})
    {
      const std::string name =
        gluing == Gluing::chain ? "chain" : "orthonormal";
      decomposition::DecompositionParameters parameters;
      parameters.partitioner =
        decomposition::DecompositionParameters::Partitioner::bisection;
      parameters.gluing = gluing;
      compare<3>(
        "L. brick 4 x 8 x 4, 8 boxes, " + name + " gluing rows",
        {body.get()},
        {brick_pair()},
        {8},
        "auto",
        [&](const decomposition::TFETIDual<3> &tfeti)
        {
          const auto [defect, sum] = gluing_gram_defect(tfeti);
          if (gluing == Gluing::orthonormal)
            check(defect < 1e-14,
                  "  orthonormal: largest |B B' - I| on the gluing "
                  "rows",
                  defect);
          else
            check(defect >= 1.,
                  "  chain: largest |B B' - I| on the gluing rows (2 on the "
                  "diagonal)",
                  defect);
          check(sum < 1e-14,
                "  " + name + ": largest |row sum| of a gluing row",
                sum);
        },
        contact::WorkingSetParameters(),
        parameters);
    }
  }


  /** M. K_s^+ of every subdomain: (I - R R') on K's range, 0 on R. */
  void
  pseudoinverse()
  {
    std::cout << "M. pseudoinverse K_s^+" << std::endl;
    const auto                              body = brick_body();
    const contact::ContactDiscretization<3> contact({body.get()},
                                                    {brick_pair()});
    decomposition::DecompositionParameters  parameters;
    parameters.subdomains_per_body = {16};
    // a preconditioner keeps K_s (without one it is released)
    parameters.preconditioner = "lumped";
    decomposition::TFETIDual<3> tfeti({body.get()},
                                      contact,
                                      parameters,
                                      cholmod());
    double                      inverse_error = 0., kernel_part = 0.;
    for (unsigned int s = 0; s < tfeti.n_subdomains(); ++s)
    {
      const auto                        &subdomain = tfeti.subdomain(s);
      const std::vector<Vector<double>> &R         = subdomain.modes();
      const unsigned int                 n         = subdomain.n_dofs();
      Vector<double>                     x(n), Kx(n), z(n), expected(n);
      for (unsigned int i = 0; i < n; ++i)
        x(i) = std::sin(1. + 7. * i + s) + 0.5; // a rigid part too
      subdomain.stiffness_matrix().vmult(Kx, x);
      subdomain.apply_pseudoinverse(z, Kx);
      expected = x;
      for (const Vector<double> &r : R)
        expected.add(-(r * x), r);
      z -= expected;
      inverse_error = std::max(inverse_error, z.l2_norm() / expected.l2_norm());
      // b = x itself: K^+ b must be orthogonal to R
      subdomain.apply_pseudoinverse(z, x);
      for (const Vector<double> &r : R)
        kernel_part = std::max(kernel_part, std::abs(r * z) / z.l2_norm());
    }
    check(inverse_error < 1e-8,
          "  largest |K^+ K x - (x - R R'x)| / |x - R R'x| over the "
          "subdomains",
          inverse_error);
    check(kernel_part < 1e-12,
          "  largest |r' K^+ b| / |K^+ b| over the subdomains and modes",
          kernel_part);
  }
} // namespace


int
main()
{
  brick();
  coulomb_block();
  floating_block();
  cantilever();
  two_blocks();
  coarse_projector();
  lumped_preconditioner();
  dirichlet_preconditioner();
  bad_counts();
  hanging_nodes();
  separated_rows();
  bisection();
  gluing_rows();
  pseudoinverse();
  return test_tools::finish();
}
