#pragma once

// A unit box body for the contact tests: [0,1]^(dim-1) x [bottom, bottom+1],
// n cells per direction, one material (E [Pa], nu = 0.3), boundary ids
// 2 d (low face) and 2 d + 1 (high face) along direction d; optionally the
// cells whose centre satisfies refine_cell_at refined once.

#include <deal.II/grid/grid_generator.h>

#include <deal.II/base/function.h>

#include <contact/contact_pair.h>
#include <fem/elastic_body.h>

#include <functional>
#include <memory>
#include <string>

template <int dim>
std::unique_ptr<dualcontact::fem::ElasticBody<dim>>
make_unit_box(
  const std::string                                     &name,
  const double                                           bottom,
  const unsigned int                                     n,
  const unsigned int                                     degree,
  const double                                           E              = 1e9,
  const std::function<bool(const dealii::Point<dim> &)> &refine_cell_at = {})
{
  using namespace dealii;
  auto       tria = std::make_shared<Triangulation<dim>>();
  Point<dim> p1, p2;
  for (unsigned int d = 0; d < dim; ++d)
    p2[d] = 1;
  p1[dim - 1] = bottom;
  p2[dim - 1] = bottom + 1;
  GridGenerator::subdivided_hyper_rectangle(
    *tria, std::vector<unsigned int>(dim, n), p1, p2, true);
  if (refine_cell_at)
  {
    // once, where the predicate holds at the cell's center: hanging nodes
    for (const auto &cell : tria->active_cell_iterators())
      if (refine_cell_at(cell->center()))
        cell->set_refine_flag();
    tria->execute_coarsening_and_refinement();
  }
  for (const auto &cell : tria->active_cell_iterators())
    cell->set_material_id(0);
  return std::make_unique<dualcontact::fem::ElasticBody<dim>>(
    name,
    tria,
    degree,
    std::map<types::material_id, dualcontact::fem::IsotropicMaterial>{
      {0, dualcontact::fem::IsotropicMaterial(E, 0.3)}});
}


/**
 * Two unit boxes stacked along the last axis: the lower one [0, 1] (E 1e9,
 * @p n_lower cells per direction, optionally refined where @p refine_lower_at
 * holds) clamped at its bottom, the upper one [1, 2] (E 2e9, @p n_upper
 * cells) with no Dirichlet condition, pressed by the traction (tau, 0, -p)
 * on its top, and a Tresca pair (slip bound g [Pa], first tangent x) of the
 * upper bottom on the lower top.  The bodies are set up and assembled.
 */
template <int dim>
struct PressedBlocks
{
  std::unique_ptr<dualcontact::fem::ElasticBody<dim>> lower, upper;
  dualcontact::contact::ContactPair<dim>              pair;

  PressedBlocks(
    const unsigned int                                     n_lower,
    const unsigned int                                     n_upper,
    const unsigned int                                     degree,
    const double                                           p,
    const double                                           tau,
    const double                                           g,
    const std::function<bool(const dealii::Point<dim> &)> &refine_lower_at = {})
  {
    using namespace dealii;
    const types::boundary_id bottom = 2 * (dim - 1), top = 2 * dim - 1;
    lower =
      make_unit_box<dim>("lower", 0, n_lower, degree, 1e9, refine_lower_at);
    upper = make_unit_box<dim>("upper", 1, n_upper, degree, 2e9);
    lower->set_dirichlet_conditions(
      {{bottom,
        ComponentMask(dim, true),
        std::make_shared<Functions::ZeroFunction<dim>>(dim)}});
    std::vector<double> traction(dim, 0.);
    traction[0]       = tau;
    traction[dim - 1] = -p;
    upper->set_traction_conditions(
      {{top, std::make_shared<Functions::ConstantFunction<dim>>(traction)}});
    for (auto *body : {lower.get(), upper.get()})
    {
      body->setup();
      body->assemble();
    }
    pair.name            = "upper-lower";
    pair.slave_body      = 1;
    pair.slave_boundary  = bottom;
    pair.master_body     = 0;
    pair.master_boundary = top;
    pair.friction.type =
      dualcontact::contact::FrictionLaw::Type::tresca_isotropic;
    pair.friction.first             = g;
    pair.first_tangent_direction[0] = 1;
  }
};
