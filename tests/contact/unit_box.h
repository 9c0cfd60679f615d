#pragma once

// A unit box body for the contact tests: [0,1]^(dim-1) x [bottom, bottom+1],
// n cells per direction, one material (E [Pa], nu = 0.3), boundary ids
// 2 d (low face) and 2 d + 1 (high face) along direction d; optionally the
// cells whose centre satisfies refine_cell_at refined once.

#include <deal.II/grid/grid_generator.h>

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
