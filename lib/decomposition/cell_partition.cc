#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <decomposition/cell_partition.h>

#include <algorithm>
#include <limits>
#include <numeric>

namespace dualcontact
{
  namespace decomposition
  {
    using namespace dealii;

    namespace
    {
      /**
       * Cuts the cells [@p begin, @p end) (indices into @p centres,
       * reordered in place) into @p n_parts parts, numbered from
       * @p first_part in @p part.
       */
      template <int dim>
      void
      bisect(const std::vector<Point<dim>>            &centres,
             const std::vector<unsigned int>::iterator begin,
             const std::vector<unsigned int>::iterator end,
             const unsigned int                        n_parts,
             const unsigned int                        first_part,
             std::vector<unsigned int>                &part)
      {
        if (n_parts == 1)
        {
          for (auto c = begin; c != end; ++c)
            part[*c] = first_part;
          return;
        }
        Point<dim> low = centres[*begin], high = centres[*begin];
        for (auto c = begin; c != end; ++c)
          for (unsigned int d = 0; d < dim; ++d)
          {
            low[d]  = std::min(low[d], centres[*c][d]);
            high[d] = std::max(high[d], centres[*c][d]);
          }
        unsigned int axis = 0;
        for (unsigned int d = 1; d < dim; ++d)
          if (high[d] - low[d] > high[axis] - low[axis])
            axis = d;
        // a strict order (the other coordinates, then the index, break
        // ties), so that a cut through a layer of equal centres is the
        // same on every process
        const auto before =
          [&centres, axis](const unsigned int a, const unsigned int b)
        {
          for (unsigned int k = 0; k < dim; ++k)
          {
            const unsigned int d = (axis + k) % dim;
            if (centres[a][d] != centres[b][d])
              return centres[a][d] < centres[b][d];
          }
          return a < b;
        };
        const unsigned int n_first = n_parts / 2;
        const auto         n_cells = static_cast<unsigned long>(end - begin);
        const auto middle = begin + (n_cells * n_first + n_parts / 2) / n_parts;
        std::nth_element(begin, middle, end, before);
        bisect(centres, begin, middle, n_first, first_part, part);
        bisect(
          centres, middle, end, n_parts - n_first, first_part + n_first, part);
      }
    } // namespace


    template <int dim>
    std::vector<unsigned int>
    bisect_cells(const Triangulation<dim> &triangulation,
                 const unsigned int        n_parts)
    {
      const unsigned int      n_cells = triangulation.n_active_cells();
      std::vector<Point<dim>> centres(n_cells);
      for (const auto &cell : triangulation.active_cell_iterators())
        centres[cell->active_cell_index()] = cell->center();
      std::vector<unsigned int> order(n_cells), part(n_cells, 0);
      std::iota(order.begin(), order.end(), 0u);
      bisect(centres, order.begin(), order.end(), n_parts, 0, part);
      return part;
    }


    template <int dim>
    std::vector<unsigned int>
    partition_cells(const Triangulation<dim>                  &triangulation,
                    const unsigned int                         n_parts,
                    const DecompositionParameters::Partitioner partitioner,
                    const std::string                         &body_name)
    {
      const unsigned int n_cells = triangulation.n_active_cells();
      const std::string  parameters =
        "(`Subdomains per body' or `Cells per subdomain' in `subsection "
        "Decomposition')";
      AssertThrow(n_parts >= 1 && n_parts <= n_cells,
                  ExcMessage(body_name + " has " + std::to_string(n_cells) +
                             " cells and cannot be cut into " +
                             std::to_string(n_parts) + " subdomains " +
                             parameters + "."));
      std::vector<unsigned int> part(n_cells, 0);
      if (partitioner == DecompositionParameters::Partitioner::bisection)
        part = bisect_cells(triangulation, n_parts);
      else if (n_parts > 1)
      {
        DynamicSparsityPattern connectivity;
        GridTools::get_face_connectivity_of_cells(triangulation, connectivity);
        SparsityPattern graph;
        graph.copy_from(connectivity);
        SparsityTools::partition(graph,
                                 n_parts,
                                 part,
                                 SparsityTools::Partitioner::metis);
      }
      std::vector<unsigned int> size(n_parts, 0);
      for (const unsigned int p : part)
        ++size[p];
      for (unsigned int p = 0; p < n_parts; ++p)
        AssertThrow(
          size[p] > 0,
          ExcMessage("The partitioner left subdomain " + std::to_string(p + 1) +
                     " of " + std::to_string(n_parts) + " of " + body_name +
                     " empty: ask for fewer subdomains " + parameters + "."));

      // The pieces of every part connected through whole faces, by
      // breadth-first search from the lowest unvisited cell, numbered by
      // their first cell.  A refined cell and a coarser neighbour share
      // one vertex only (the others of the fine face hang, and TFETI glues
      // hanging nodes by multiplier rows, not inside K_s): joined in one
      // subdomain they would hinge about that vertex.
      std::vector<typename Triangulation<dim>::active_cell_iterator> cells(
        n_cells);
      for (const auto &cell : triangulation.active_cell_iterators())
        cells[cell->active_cell_index()] = cell;
      const unsigned int        none = std::numeric_limits<unsigned int>::max();
      std::vector<unsigned int> subdomain(n_cells, none);
      std::vector<unsigned int> queue;
      unsigned int              n_subdomains = 0;
      for (unsigned int seed = 0; seed < n_cells; ++seed)
      {
        if (subdomain[seed] != none)
          continue;
        queue.assign(1, seed);
        subdomain[seed] = n_subdomains;
        for (unsigned int q = 0; q < queue.size(); ++q)
        {
          const auto &cell = cells[queue[q]];
          for (const unsigned int f : cell->face_indices())
          {
            if (cell->at_boundary(f) || cell->face(f)->has_children() ||
                cell->neighbor(f)->level() != cell->level() ||
                !cell->neighbor(f)->is_active())
              continue;
            const unsigned int neighbour =
              cell->neighbor(f)->active_cell_index();
            if (subdomain[neighbour] == none &&
                part[neighbour] == part[queue[q]])
            {
              subdomain[neighbour] = n_subdomains;
              queue.push_back(neighbour);
            }
          }
        }
        ++n_subdomains;
      }
      return subdomain;
    }


    template std::vector<unsigned int>
    partition_cells(const Triangulation<2> &,
                    const unsigned int,
                    const DecompositionParameters::Partitioner,
                    const std::string &);
    template std::vector<unsigned int>
    partition_cells(const Triangulation<3> &,
                    const unsigned int,
                    const DecompositionParameters::Partitioner,
                    const std::string &);
    template std::vector<unsigned int>
    bisect_cells(const Triangulation<2> &, const unsigned int);
    template std::vector<unsigned int>
    bisect_cells(const Triangulation<3> &, const unsigned int);
  } // namespace decomposition
} // namespace dualcontact
