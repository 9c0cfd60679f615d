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

      // The face-connected pieces of every part, by breadth-first search
      // from the lowest unvisited cell: numbered by their first cell.
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
          for (auto it = graph.begin(queue[q]); it != graph.end(queue[q]); ++it)
          {
            const unsigned int neighbour = it->column();
            if (subdomain[neighbour] == none &&
                part[neighbour] == part[queue[q]])
            {
              subdomain[neighbour] = n_subdomains;
              queue.push_back(neighbour);
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
