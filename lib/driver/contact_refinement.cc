#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/rtree.h>

#include <driver/contact_refinement.h>
#include <io/parameter_file.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <numeric>
#include <set>

namespace dualcontact
{
  namespace driver
  {
    namespace
    {
      const std::string subsection = "Contact refinement";

      /**
       * The number of active cells of @p tria flagged for refinement and
       * the bounding box (lower, upper corner) of their vertices; lower >
       * upper when none.
       */
      template <int dim>
      std::pair<unsigned int, std::pair<dealii::Point<dim>, dealii::Point<dim>>>
      flagged_box(const dealii::Triangulation<dim> &tria)
      {
        dealii::Point<dim> lower, upper;
        for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = std::numeric_limits<double>::max();
          upper[d] = -std::numeric_limits<double>::max();
        }
        unsigned int n = 0;
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->refine_flag_set())
          {
            ++n;
            for (const unsigned int v : cell->vertex_indices())
              for (unsigned int d = 0; d < dim; ++d)
              {
                lower[d] = std::min(lower[d], cell->vertex(v)[d]);
                upper[d] = std::max(upper[d], cell->vertex(v)[d]);
              }
          }
        return {n, {lower, upper}};
      }
    } // namespace


    template <int dim>
    void
    ContactRefinement<dim>::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection(subsection);
      prm.declare_entry(
        "Cycles",
        "0",
        dealii::Patterns::Integer(0, 50),
        "Number of contact-zone refinement cycles [-]: solve, mark the "
        "cells at the contact zone (and by the error indicator), refine, "
        "solve again, this many times; 0 (default) = off, one solve on the "
        "meshes as given. The output is the last solve's; results.txt and "
        "statistics.json record every solve (`refinement.cycle_K.*').");
      prm.declare_entry(
        "Pairs",
        "all",
        dealii::Patterns::Anything(),
        "The contact pairs whose zones are refined: `all' or a list of pair "
        "numbers (as in `Contact pair N'), e.g. `1, 3'. Their slave bodies "
        "are refined at the contact nodes, their master bodies (body-body "
        "pairs) at the nodes' closest master points, and the error "
        "indicator marks cells of both.");
      prm.declare_entry(
        "Gap threshold",
        "0",
        dealii::Patterns::Double(0.),
        "Besides the nodes in contact (not separated, see `Output/Contact "
        "status tolerance'), the cells at slave nodes whose gap after the "
        "solve is below this [m] are refined (where the contact zone may "
        "grow under a finer mesh); 0 = the nodes in contact only.");
      prm.declare_entry(
        "Zone factor",
        "0.25",
        dealii::Patterns::Double(0.),
        "Besides the cells at the marked nodes, the cells within this "
        "factor [-] times the size of the pair's marked zone (the diagonal "
        "of the bounding box of its marked nodes) of a marked node are "
        "refined too: the stresses under a contact zone vary over a depth "
        "of the zone's size, which the cells at the surface alone do not "
        "resolve (refined, they form a fine skin over a coarse body and the "
        "pressure stops converging, doc/hertz.md). 0 = only the cells with "
        "a marked node.");
      prm.declare_entry(
        "Indicator fraction",
        "0.1",
        dealii::Patterns::Double(0., 1.),
        "Fraction [-] of the cells of every body of a selected pair with the "
        "largest Kelly error indicator of the displacement (jumps of the "
        "normal derivative across faces) refined in addition to the contact "
        "zone; 0 = contact zone only, 1 = every cell with a "
        "non-zero indicator.");
      prm.declare_entry("Maximum level",
                        "0",
                        dealii::Patterns::Integer(0, 100),
                        "Cells of this refinement level [-] (0 = the "
                        "coarse cells of the mesh generator or file) or "
                        "finer are not marked; 0 = no limit.");
      prm.declare_entry("Maximum dofs",
                        "0",
                        dealii::Patterns::Integer(0),
                        "No further cycle is started once the bodies have "
                        "this many dofs [-] in total; 0 = no limit.");
      prm.leave_subsection();
    }


    template <int dim>
    ContactRefinement<dim>::ContactRefinement(dealii::ParameterHandler &prm,
                                              const unsigned int        n_pairs)
    {
      prm.enter_subsection(subsection);
      n_cycles_           = prm.get_integer("Cycles");
      const std::string p = dealii::Utilities::trim(prm.get("Pairs"));
      gap_threshold_      = prm.get_double("Gap threshold");
      zone_factor_        = prm.get_double("Zone factor");
      indicator_fraction_ = prm.get_double("Indicator fraction");
      max_level_          = prm.get_integer("Maximum level");
      max_dofs_           = prm.get_integer("Maximum dofs");
      prm.leave_subsection();

      AssertThrow(n_cycles_ == 0 || n_pairs > 0,
                  dealii::ExcMessage(
                    "Contact refinement needs contact pairs: the scene has "
                    "none, set the cycles to 0. " +
                    io::parameter_location(subsection, "Cycles")));
      all_pairs_ = p == "all";
      if (all_pairs_)
        for (unsigned int n = 0; n < n_pairs; ++n)
          pairs_.push_back(n);
      else
      {
        for (const auto &item : dealii::Utilities::split_string_list(p))
        {
          int number = 0;
          try
          {
            number = dealii::Utilities::string_to_int(item);
          }
          catch (...)
          {
            number = 0;
          }
          AssertThrow(number >= 1 &&
                        static_cast<unsigned int>(number) <= n_pairs,
                      dealii::ExcMessage(
                        "`" + item +
                        "' is no contact pair: expected `all' or numbers "
                        "from 1 to " +
                        std::to_string(n_pairs) + ". " +
                        io::parameter_location(subsection, "Pairs")));
          pairs_.push_back(number - 1);
        }
        AssertThrow(!pairs_.empty(),
                    dealii::ExcMessage(
                      "No contact pair given: expected `all' or a list of "
                      "pair numbers. " +
                      io::parameter_location(subsection, "Pairs")));
      }
    }


    template <int dim>
    void
    ContactRefinement<dim>::check_meshes(const Scene<dim> &scene) const
    {
      if (n_cycles_ == 0)
        return;
      for (const auto p : pairs_)
      {
        const auto &pair = scene.pair_parameters()[p].pair;
        std::vector<unsigned int> bodies = {pair.slave_body};
        if (!pair.obstacle)
          bodies.push_back(pair.master_body);
        for (const unsigned int b : bodies)
        {
          const fem::CellFamily<dim> &family = scene.body(b).cell_family();
          if (!family.is_simplex())
            continue;
          const std::string name = scene.body(b).name();
          AssertThrow(dim == 2,
                      dealii::ExcMessage(
                        "Contact refinement of pair `" + pair.name +
                        "' would refine " + name +
                        " locally, but its mesh has tetrahedra, and deal.II "
                        "9.4 has no hanging nodes on tetrahedra: set the "
                        "cycles to 0 " +
                        io::parameter_location(subsection, "Cycles") +
                        " and refine globally, or mesh " + name +
                        " with hexahedra."));
          AssertThrow(!(indicator_fraction_ > 0),
                      dealii::ExcMessage(
                        "The error indicator of contact refinement (Kelly's) "
                        "has no simplex faces in deal.II 9.4, and " + name +
                        " has triangles: set it to 0 " +
                        io::parameter_location(subsection,
                                               "Indicator fraction") +
                        " (the contact zone is refined all the same)."));
        }
      }
    }


    template <int dim>
    std::string
    ContactRefinement<dim>::description() const
    {
      std::string text;
      for (const auto p : pairs_)
        text += (text.empty() ? "" : ", ") + std::to_string(p + 1);
      return all_pairs_ ? "all pairs" : "pairs " + text;
    }


    template <int dim>
    typename ContactRefinement<dim>::CycleRecord
    ContactRefinement<dim>::record(const unsigned int       cycle,
                                   const Scene<dim>        &scene,
                                   const ContactStage<dim> &contact,
                                   const double             wall_time) const
    {
      CycleRecord r;
      r.cycle     = cycle;
      r.wall_time = wall_time;
      for (unsigned int b = 0; b < scene.n_bodies(); ++b)
      {
        r.n_cells.push_back(
          scene.body(b).triangulation().n_global_active_cells());
        r.n_dofs.push_back(scene.body(b).n_dofs());
      }
      for (const auto &pair : contact.pair_results())
      {
        const unsigned int in_contact = pair.n_nodes - pair.n_separated;
        r.n_contact_nodes += pair.n_nodes;
        r.n_in_contact += in_contact;
        r.pair_nodes.push_back(pair.n_nodes);
        r.pair_in_contact.push_back(in_contact);
        r.pair_normal_force.push_back(pair.normal_force);
        r.pair_max_pressure.push_back(pair.max_pressure);
      }
      for (const auto &q : contact.result().qp_statistics)
      {
        r.qp_iterations += q.iterations;
        r.qp_hessian_products += q.n_hessian_products;
      }
      return r;
    }


    template <int dim>
    void
    ContactRefinement<dim>::mark(Scene<dim>              &scene,
                                 const ContactStage<dim> &contact,
                                 CycleRecord             &record) const
    {
      const unsigned int n_bodies = scene.n_bodies();
      std::vector<bool>  selected_body(n_bodies, false);
      std::vector<bool>  selected_pair(scene.pair_parameters().size(), false);
      for (const auto p : pairs_)
      {
        selected_pair[p]               = true;
        const auto &pair               = scene.pair_parameters()[p].pair;
        selected_body[pair.slave_body] = true;
        if (!pair.obstacle)
          selected_body[pair.master_body] = true;
      }

      // 1. The contact zone: the marked nodes (in contact, or closer than
      // the gap threshold) and the closest master points of body-body
      // pairs; the cells with a dof of a marked slave node, the master
      // cells at the master points, and the cells within zone factor times
      // the zone's size of them.
      const auto &discretization = contact.discretization();
      const auto &surfaces       = contact.surfaces();
      // per body, per pair: the marked points (slave node positions or
      // master points)
      std::vector<std::map<unsigned int, std::vector<dealii::Point<dim>>>>
                                                             points(n_bodies);
      std::vector<std::set<dealii::types::global_dof_index>> slave_dofs(
        n_bodies);
      std::vector<unsigned int> index_in_pair(surfaces.size(), 0);
      for (const auto &node : discretization.nodes())
      {
        const auto &out = surfaces[node.pair][index_in_pair[node.pair]++];
        if (!selected_pair[node.pair])
          continue;
        if (out.status == io::contact_status::separated &&
            !(out.gap < gap_threshold_))
          continue;
        slave_dofs[node.body].insert(node.dofs.begin(), node.dofs.end());
        points[node.body][node.pair].push_back(node.position);
        const auto &pair = scene.pair_parameters()[node.pair].pair;
        if (!pair.obstacle)
        {
          points[pair.master_body][node.pair].push_back(node.master_point);
          const fem::ElasticBody<dim> &master = scene.body(pair.master_body);
          // (triangles: deal.II 9.4's MappingFE cannot invert a point;
          // the zone below marks around the master point all the same)
          if (!master.cell_family().is_simplex())
          try
          {
            const auto found = dealii::GridTools::find_active_cell_around_point(
              master.mapping(),
              scene.triangulation(pair.master_body),
              node.master_point);
            found.first->set_refine_flag();
          }
          catch (const std::exception &)
          {
            // a closest point on the master surface is in a master cell;
            // round-off may put it just outside: the zone marks around it
          }
        }
      }
      for (unsigned int b = 0; b < n_bodies; ++b)
      {
        std::vector<dealii::types::global_dof_index> cell_dofs(
          scene.body(b).fe().n_dofs_per_cell());
        // the zones of the pairs on this body: rtree of the points, radius
        std::vector<
          std::pair<decltype(dealii::pack_rtree(
                      std::declval<std::vector<dealii::Point<dim>>>())),
                    double>>
          zones;
        if (zone_factor_ > 0)
          for (const auto &[p, zone_points] : points[b])
          {
            dealii::Point<dim> lower = zone_points[0], upper = zone_points[0];
            for (const auto &x : zone_points)
              for (unsigned int d = 0; d < dim; ++d)
              {
                lower[d] = std::min(lower[d], x[d]);
                upper[d] = std::max(upper[d], x[d]);
              }
            zones.emplace_back(dealii::pack_rtree(zone_points),
                               zone_factor_ * lower.distance(upper));
          }
        if (slave_dofs[b].empty() && zones.empty())
          continue;
        for (const auto &cell :
             scene.body(b).dof_handler().active_cell_iterators())
        {
          bool mark = false;
          if (!slave_dofs[b].empty())
          {
            cell->get_dof_indices(cell_dofs);
            for (const auto dof : cell_dofs)
              if (slave_dofs[b].count(dof) > 0)
              {
                mark = true;
                break;
              }
          }
          const dealii::Point<dim> center = cell->center();
          for (unsigned int z = 0; !mark && z < zones.size(); ++z)
          {
            std::vector<dealii::Point<dim>> nearest;
            zones[z].first.query(boost::geometry::index::nearest(center, 1),
                                 std::back_inserter(nearest));
            mark =
              !nearest.empty() && center.distance(nearest[0]) <=
                                    zones[z].second + 0.5 * cell->diameter();
          }
          if (mark)
            cell->set_refine_flag();
        }
      }

      // the contact zone's own flags (before the indicator and the
      // hanging-node balance add theirs): where the zone criteria refine
      record.n_zone_cells = 0;
      record.zone_box.clear();
      for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const auto box = flagged_box(scene.triangulation(b));
        record.n_zone_cells += box.first;
        record.zone_box.push_back(box.second);
      }

      // 2. The error indicator (adds to the contact zone's flags).
      if (indicator_fraction_ > 0)
        for (unsigned int b = 0; b < n_bodies; ++b)
          if (selected_body[b])
          {
            const fem::ElasticBody<dim> &body = scene.body(b);
            dealii::Vector<float>        indicator(
              body.triangulation().n_active_cells());
            dealii::KellyErrorEstimator<dim>::estimate(body.mapping(),
                                                       body.dof_handler(),
                                                       dealii::QGauss<dim - 1>(
                                                         body.fe().degree + 1),
                                                       {},
                                                       scene.displacements()[b],
                                                       indicator);
            // a parallel (shared) mesh: each process estimates its own
            // cells, zero elsewhere; the sum is the whole indicator on every
            // process, so that all mark alike
            if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
            {
              std::vector<float> local(indicator.begin(), indicator.end()),
                total(local.size());
              dealii::Utilities::MPI::sum(local, MPI_COMM_WORLD, total);
              std::copy(total.begin(), total.end(), indicator.begin());
            }
            std::vector<unsigned int> order(indicator.size());
            std::iota(order.begin(), order.end(), 0u);
            std::stable_sort(order.begin(),
                             order.end(),
                             [&](const unsigned int i, const unsigned int j)
                             { return indicator[i] > indicator[j]; });
            const unsigned int n_mark = static_cast<unsigned int>(
              std::ceil(indicator_fraction_ * indicator.size()));
            std::vector<bool> marked(indicator.size(), false);
            for (unsigned int k = 0; k < n_mark && k < order.size(); ++k)
              if (indicator[order[k]] > 0)
                marked[order[k]] = true;
            for (const auto &cell : body.dof_handler().active_cell_iterators())
              if (marked[cell->active_cell_index()])
                cell->set_refine_flag();
          }

      // 3. The level limit; then the flags the mesh adds to keep one
      // hanging node per face (prepare_coarsening_and_refinement), so that
      // the count and the boxes say what will be refined.
      record.n_marked_cells = 0;
      record.marked_box.clear();
      for (unsigned int b = 0; b < n_bodies; ++b)
      {
        dealii::Triangulation<dim> &tria = scene.triangulation(b);
        if (max_level_ > 0)
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->refine_flag_set() &&
                static_cast<unsigned int>(cell->level()) >= max_level_)
              cell->clear_refine_flag();
        tria.prepare_coarsening_and_refinement();
        const auto box = flagged_box(tria);
        record.n_marked_cells += box.first;
        record.marked_box.push_back(box.second);
      }
    }


    template class ContactRefinement<2>;
    template class ContactRefinement<3>;
  } // namespace driver
} // namespace dualcontact
