// decomposition::MethodChoice, `Decomposition/Method = automatic': on a
// small clamped brick the undecomposed dual is estimated faster and chosen,
// with both estimates computed from symbolic analyses (the subdomains as
// TFETIDual cuts them: ceil(cells / `Cells per subdomain')); a memory limit
// below the undecomposed factor chooses TFETI whatever the times; an
// explicit method is taken as given without an analysis; the products
// model grows with the digits asked for; the TFETI estimate's factors are
// far smaller than the whole body's (nested dissection: flops ~ n^2 in 3D).
// And the crossover measured on the thesis' brick at 30 x 60 x 30 (1e-6,
// doc/benchmarks/tfeti.md, "Automatic choice"): undecomposed on one
// process, TFETI on two.

#include <deal.II/grid/grid_generator.h>

#include <decomposition/method_choice.h>
#include <fem/elastic_body.h>

#include <test_tools.h>

#include <iostream>

using namespace dealii;
using namespace dualcontact;
using test_tools::check;

int
main()
{
  auto tria = std::make_shared<Triangulation<3>>();
  GridGenerator::subdivided_hyper_rectangle(
    *tria, {8, 16, 8}, Point<3>(), Point<3>(1, 2, 1), true);
  for (const auto &cell : tria->active_cell_iterators())
    cell->set_material_id(0);
  const fem::IsotropicMaterial material(2e11, 0.3);
  fem::ElasticBody<3>          body("brick", tria, 1, {{0, material}});
  body.set_dirichlet_conditions(
    {{2,
      ComponentMask(3, true),
      std::make_shared<Functions::ZeroFunction<3>>(3)}});
  body.setup();
  const std::vector<const fem::ElasticBody<3> *> bodies{&body};

  using Method = decomposition::DecompositionParameters::Method;
  decomposition::DecompositionParameters parameters;
  parameters.cells_per_subdomain = 256;
  {
    const decomposition::MethodChoice<3> choice(
      bodies, parameters, 1e-6, 1, 1, false);
    std::cout << choice.description() << std::endl;
    check(choice.method() == Method::none,
          "small brick: the undecomposed dual",
          choice.undecomposed().seconds());
    check(choice.undecomposed().computed && choice.tfeti().computed,
          "both estimated");
    check(choice.tfeti().n_subdomains == 4,
          "TFETI estimate: 1,024 cells / 256 = 4 subdomains",
          choice.tfeti().n_subdomains);
    check(choice.undecomposed().seconds() < choice.tfeti().seconds(),
          "undecomposed estimate below TFETI's",
          choice.tfeti().seconds());
    check(choice.tfeti().factor_flops <
            0.5 * choice.undecomposed().factor_flops,
          "the subdomains' factorizations cost less than the whole body's",
          choice.tfeti().factor_flops / choice.undecomposed().factor_flops);
    check(choice.undecomposed().megabytes > 0 && choice.tfeti().megabytes > 0,
          "factor sizes estimated",
          choice.undecomposed().megabytes);
    check(choice.description().find("undecomposed dual") != std::string::npos,
          "the log line says the choice");
  }
  {
    decomposition::DecompositionParameters tight = parameters;
    tight.memory_limit = 0.5; // MB: below the brick's factor
    const decomposition::MethodChoice<3> choice(
      bodies, tight, 1e-6, 1, 1, false);
    std::cout << choice.description() << std::endl;
    check(choice.method() == Method::tfeti,
          "memory limit below the factor: TFETI");
    check(choice.description().find("Memory limit") != std::string::npos,
          "the log line names `Memory limit'");
  }
  {
    decomposition::DecompositionParameters given = parameters;
    given.method                                 = Method::none;
    const decomposition::MethodChoice<3> choice(
      bodies, given, 1e-6, 1, 1, false);
    check(choice.method() == Method::none && !choice.undecomposed().computed,
          "an explicit method without analysis");
  }
  {
    // the brick of inputs/brick.prm at level 30: 1 x 2 x 1, Q1, the face
    // y = 0 clamped, 1,000 cells a subdomain (the defaults)
    auto brick = std::make_shared<Triangulation<3>>();
    GridGenerator::subdivided_hyper_rectangle(
      *brick, {30, 60, 30}, Point<3>(), Point<3>(1, 2, 1), true);
    for (const auto &cell : brick->active_cell_iterators())
      cell->set_material_id(0);
    fem::ElasticBody<3> level_30("brick", brick, 1, {{0, material}});
    level_30.set_dirichlet_conditions(
      {{2,
        ComponentMask(3, true),
        std::make_shared<Functions::ZeroFunction<3>>(3)}});
    level_30.setup();
    decomposition::DecompositionParameters defaults;
    for (const unsigned int n_processes : {1u, 2u})
    {
      const decomposition::MethodChoice<3> choice(
        {&level_30}, defaults, 1e-6, n_processes, n_processes, false);
      std::cout << choice.description() << std::endl;
      const Method expected = n_processes == 1 ? Method::none : Method::tfeti;
      check(choice.method() == expected,
            "brick 30 x 60 x 30 on " + std::to_string(n_processes) +
              " process(es): " + (n_processes == 1 ? "undecomposed" : "TFETI") +
              " (measured)",
            std::to_string(choice.undecomposed().seconds()) + " s against " +
              std::to_string(choice.tfeti().seconds()) + " s");
    }
  }
  check(decomposition::MethodChoice<3>::tfeti_products(1e-6) >
          decomposition::MethodChoice<3>::tfeti_products(1e-4),
        "products grow with the digits",
        decomposition::MethodChoice<3>::tfeti_products(1e-6));
  return test_tools::failures == 0 ? 0 : 1;
}
