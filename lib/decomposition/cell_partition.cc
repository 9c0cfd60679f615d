#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <decomposition/cell_partition.h>

#include <limits>

namespace dualcontact
{
  namespace decomposition
  {
    using namespace dealii;

    template <int dim>
    std::vector<unsigned int>
    partition_cells(const Triangulation<dim> &triangulation,
                    const unsigned int        n_parts,
                    const std::string        &body_name)
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
      DynamicSparsityPattern connectivity;
      GridTools::get_face_connectivity_of_cells(triangulation, connectivity);
      SparsityPattern graph;
      graph.copy_from(connectivity);

      std::vector<unsigned int> part(n_cells, 0);
      if (n_parts > 1)
        SparsityTools::partition(graph,
                                 n_parts,
                                 part,
                                 SparsityTools::Partitioner::metis);
      std::vector<unsigned int> size(n_parts, 0);
      for (const unsigned int p : part)
        ++size[p];
      for (unsigned int p = 0; p < n_parts; ++p)
        AssertThrow(size[p] > 0,
                    ExcMessage("METIS left subdomain " + std::to_string(p + 1) +
                               " of " + std::to_string(n_parts) + " of " +
                               body_name + " empty: ask for fewer subdomains " +
                               parameters + "."));

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
                    const std::string &);
    template std::vector<unsigned int>
    partition_cells(const Triangulation<3> &,
                    const unsigned int,
                    const std::string &);
  } // namespace decomposition
} // namespace dualcontact
