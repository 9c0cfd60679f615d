#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>

#include <decomposition/cell_partition.h>
#include <decomposition/tfeti_dual.h>
#include <fem/rigid_body_modes.h>
#include <util/machine.h>

#include <algorithm>
#include <limits>
#include <map>
#include <set>

// TFETIDual's decomposition: the cut of the bodies into subdomains, their
// owners and dofs, and the figures of the decomposition; apart from
// tfeti_dual.cc, which holds the dual's operators and recovery, to keep
// files short.

namespace dualcontact
{
  namespace decomposition
  {
    using namespace dealii;

    namespace
    {
      const unsigned int invalid = std::numeric_limits<unsigned int>::max();
    } // namespace


    template <int dim>
    void
    TFETIDual<dim>::decompose(const DecompositionParameters &parameters)
    {
      std::vector<std::vector<typename Subdomain<dim>::CellIterator>> cells;
      std::vector<std::string>                                        names;
      std::vector<unsigned int>                                       body_of;
      first_copy_.resize(bodies_.size());
      for (unsigned int b = 0; b < bodies_.size(); ++b)
        cut_body(b, parameters, cells, names, body_of);
      first_subdomain_.push_back(cells.size());

      dofs_.resize(cells.size());
      for (unsigned int s = 0; s < cells.size(); ++s)
      {
        const fem::ElasticBody<dim>         &body = *bodies_[body_of[s]];
        std::vector<types::global_dof_index> cell_dofs(
          body.fe().n_dofs_per_cell());
        for (const auto &cell : cells[s])
        {
          cell->get_dof_indices(cell_dofs);
          dofs_[s].insert(dofs_[s].end(), cell_dofs.begin(), cell_dofs.end());
        }
        std::sort(dofs_[s].begin(), dofs_[s].end());
        dofs_[s].erase(std::unique(dofs_[s].begin(), dofs_[s].end()),
                       dofs_[s].end());
      }
      if (distributed_mesh_)
      {
        owner_ = distributed_mesh_->owners();
        AssertDimension(owner_.size(), cells.size());
        owned_.clear();
        for (unsigned int s = 0; s < owner_.size(); ++s)
          if (owner_[s] == rank_)
            owned_.push_back(s);
        gather_subdomain_dofs();
      }
      else
        assign_owners();

      subdomains_.resize(cells.size());
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        const fem::ElasticBody<dim> &body = *bodies_[b];
        first_copy_[b].assign(body.n_dofs(), {invalid, invalid});
        for (unsigned int s = first_subdomain_[b]; s < first_subdomain_[b + 1];
             ++s)
          for (unsigned int l = 0; l < dofs_[s].size(); ++l)
            if (first_copy_[b][dofs_[s][l]].first == invalid)
              first_copy_[b][dofs_[s][l]] = {s, l};
        bool owns_some = false;
        for (unsigned int s = first_subdomain_[b]; s < first_subdomain_[b + 1];
             ++s)
          owns_some = owns_some || owner_[s] == rank_;
        if (!owns_some)
          continue;

        // the support points of the dofs of this process' cells (on a
        // distributed mesh the others are not known here)
        std::map<types::global_dof_index, Point<dim>> known_points;
        DoFTools::map_dofs_to_support_points(body.mapping(),
                                             body.dof_handler(),
                                             known_points);
        std::vector<Point<dim>> points(body.n_dofs());
        for (const auto &[dof, point] : known_points)
          points[dof] = point;
        std::vector<unsigned int>            components(body.n_dofs());
        std::vector<types::global_dof_index> dofs(body.fe().n_dofs_per_cell());
        for (const auto &cell : body.dof_handler().active_cell_iterators())
        {
          if (cell->is_artificial())
            continue;
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            components[dofs[i]] = body.fe().system_to_component_index(i).first;
        }
        for (unsigned int s = first_subdomain_[b]; s < first_subdomain_[b + 1];
             ++s)
          if (owner_[s] == rank_)
          {
            subdomains_[s] = std::make_unique<Subdomain<dim>>(
              body, b, cells[s], points, components, names[s]);
            Assert(subdomains_[s]->dofs() == dofs_[s], ExcInternalError());
          }
      }
    }


    template <int dim>
    void
    TFETIDual<dim>::assign_owners()
    {
      std::vector<unsigned long> sizes(dofs_.size());
      for (unsigned int s = 0; s < dofs_.size(); ++s)
        sizes[s] = dofs_[s].size();
      owner_ = assign_subdomains_to_processes(sizes, n_processes_);
      owned_.clear();
      for (unsigned int s = 0; s < owner_.size(); ++s)
        if (owner_[s] == rank_)
          owned_.push_back(s);
    }


    template <int dim>
    void
    TFETIDual<dim>::cut_body(
      const unsigned int             b,
      const DecompositionParameters &parameters,
      std::vector<std::vector<typename Subdomain<dim>::CellIterator>> &cells,
      std::vector<std::string>                                        &names,
      std::vector<unsigned int>                                       &body_of)
    {
      const fem::ElasticBody<dim> &body = *bodies_[b];
      std::vector<unsigned int>    part;
      unsigned int                 n_pieces = 0;
      if (distributed_mesh_)
        n_pieces = distributed_mesh_->n_subdomains(b);
      else
      {
        // every process partitions (so that an error is thrown on every
        // process alike) and takes the first one's partition, so that
        // every process has the same one whatever METIS' seeding
        const unsigned int n_parts =
          parameters.n_subdomains(b, body.triangulation().n_active_cells());
        part = partition_cells(body.triangulation(),
                               n_parts,
                               parameters.partitioner,
                               body.name());
        if (n_processes_ > 1)
          part = Utilities::MPI::broadcast(communicator_, part, 0);
        n_pieces = *std::max_element(part.begin(), part.end()) + 1;
      }
      first_subdomain_.push_back(cells.size());
      cells.resize(cells.size() + n_pieces);
      for (const auto &cell : body.dof_handler().active_cell_iterators())
        if (!distributed_mesh_)
          cells[first_subdomain_.back() + part[cell->active_cell_index()]]
            .push_back(cell);
        else if (cell->is_locally_owned())
          cells[first_subdomain_.back() + distributed_mesh_->subdomain_of_cell(
                                            b, cell->active_cell_index())]
            .push_back(cell);
      for (unsigned int p = 0; p < n_pieces; ++p)
      {
        names.push_back(body.name() + ", subdomain " + std::to_string(p + 1));
        body_of.push_back(b);
      }
    }


    template <int dim>
    void
    TFETIDual<dim>::gather_subdomain_dofs()
    {
      // (subdomain, size, dofs...) of the owned subdomains, concatenated
      // over the processes: the gluing rows are numbered alike everywhere
      std::vector<double> local;
      for (const unsigned int s : owned_)
      {
        local.push_back(s);
        local.push_back(dofs_[s].size());
        local.insert(local.end(), dofs_[s].begin(), dofs_[s].end());
      }
      const std::vector<double> all =
        util::concatenate_over_processes(local, communicator_);
      for (std::size_t i = 0; i < all.size();)
      {
        const auto s    = static_cast<unsigned int>(all[i]);
        const auto size = static_cast<std::size_t>(all[i + 1]);
        std::vector<types::global_dof_index> &dofs = dofs_[s];
        dofs.resize(size);
        for (std::size_t k = 0; k < size; ++k)
          dofs[k] = static_cast<types::global_dof_index>(all[i + 2 + k]);
        i += 2 + size;
      }
    }


    template <int dim>
    bool
    TFETIDual<dim>::floats_on_distributed_mesh(const unsigned int b) const
    {
      // the support points and components of the prescribed dofs this
      // process owns, gathered: a surface's worth
      const fem::ElasticBody<dim> &body = *bodies_[b];
      const IndexSet     &owned_dofs = body.dof_handler().locally_owned_dofs();
      std::vector<double> local;
      std::vector<types::global_dof_index> dofs(body.fe().n_dofs_per_cell());
      const std::vector<Point<dim>> &unit = body.fe().get_unit_support_points();
      std::set<types::global_dof_index> listed;
      for (const auto &cell : body.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (owned_dofs.is_element(dofs[i]) &&
                listed.insert(dofs[i]).second &&
                body.constraints().is_constrained(dofs[i]) &&
                !body.hanging_node_constraints().is_constrained(dofs[i]))
            {
              const Point<dim> x =
                body.mapping().transform_unit_to_real_cell(cell, unit[i]);
              for (unsigned int d = 0; d < dim; ++d)
                local.push_back(x[d]);
              local.push_back(body.fe().system_to_component_index(i).first);
            }
        }
      const std::vector<double> all =
        util::concatenate_over_processes(local, communicator_);
      std::vector<Point<dim>>   points;
      std::vector<unsigned int> components;
      for (std::size_t i = 0; i < all.size(); i += dim + 1)
      {
        Point<dim> x;
        for (unsigned int d = 0; d < dim; ++d)
          x[d] = all[i + d];
        points.push_back(x);
        components.push_back(static_cast<unsigned int>(all[i + dim]));
      }
      return fem::RigidBodyModes<dim>::n_free_motions(points, components) > 0;
    }


    template <int dim>
    unsigned int
    TFETIDual<dim>::n_subdomains() const
    {
      return subdomains_.size();
    }


    template <int dim>
    bool
    TFETIDual<dim>::is_owned(const unsigned int s) const
    {
      AssertIndexRange(s, owner_.size());
      return owner_[s] == rank_;
    }


    template <int dim>
    const Subdomain<dim> &
    TFETIDual<dim>::subdomain(const unsigned int s) const
    {
      Assert(is_owned(s),
             ExcMessage("Subdomain " + std::to_string(s) +
                        " belongs to another process."));
      return *subdomains_[s];
    }


    template <int dim>
    const std::vector<types::global_dof_index> &
    TFETIDual<dim>::subdomain_dofs(const unsigned int s) const
    {
      AssertIndexRange(s, dofs_.size());
      return dofs_[s];
    }


    template <int dim>
    std::vector<unsigned int>
    TFETIDual<dim>::subdomains_per_process() const
    {
      std::vector<unsigned int> count(n_processes_, 0);
      for (const unsigned int p : owner_)
        ++count[p];
      return count;
    }


    template <int dim>
    std::vector<unsigned int>
    TFETIDual<dim>::subdomain_dofs_per_process() const
    {
      std::vector<unsigned int> count(n_processes_, 0);
      for (unsigned int s = 0; s < owner_.size(); ++s)
        count[owner_[s]] += dofs_[s].size();
      return count;
    }


    template <int dim>
    unsigned int
    TFETIDual<dim>::n_subdomains_of_body(const unsigned int b) const
    {
      return first_subdomain_[b + 1] - first_subdomain_[b];
    }


    template <int dim>
    unsigned int
    TFETIDual<dim>::n_primal_dofs() const
    {
      unsigned int n = 0;
      for (const auto &dofs : dofs_)
        n += dofs.size();
      return n;
    }


    template <int dim>
    unsigned int
    TFETIDual<dim>::n_gluing_multipliers() const
    {
      return rows_->n_gluing();
    }


    template <int dim>
    unsigned int
    TFETIDual<dim>::n_dirichlet_multipliers() const
    {
      return rows_->n_dirichlet();
    }


    template <int dim>
    const CoarseProblem &
    TFETIDual<dim>::coarse_problem() const
    {
      return *coarse_;
    }


    template <int dim>
    const ConstraintRows<dim> &
    TFETIDual<dim>::constraint_rows() const
    {
      return *rows_;
    }


    template <int dim>
    double
    TFETIDual<dim>::decomposition_time() const
    {
      return decomposition_time_;
    }


    template <int dim>
    double
    TFETIDual<dim>::max_interface_jump() const
    {
      return max_jump_;
    }


    template <int dim>
    double
    TFETIDual<dim>::relative_interface_jump() const
    {
      return relative_jump_;
    }

    // the members defined here, for the dimensions of TFETIDual's own
    // instantiation (tfeti_dual.cc)
#define DUALCONTACT_INSTANTIATE(dim)                                             \
  template void TFETIDual<dim>::decompose(const DecompositionParameters &);      \
  template void TFETIDual<dim>::assign_owners();                                 \
  template void TFETIDual<dim>::cut_body(                                        \
    const unsigned int,                                                          \
    const DecompositionParameters &,                                             \
    std::vector<std::vector<typename Subdomain<dim>::CellIterator>> &,           \
    std::vector<std::string> &,                                                  \
    std::vector<unsigned int> &);                                                \
  template void TFETIDual<dim>::gather_subdomain_dofs();                         \
  template bool TFETIDual<dim>::floats_on_distributed_mesh(const unsigned int)   \
    const;                                                                       \
  template unsigned int TFETIDual<dim>::n_subdomains() const;                    \
  template bool         TFETIDual<dim>::is_owned(const unsigned int) const;      \
  template const Subdomain<dim> &TFETIDual<dim>::subdomain(const unsigned int)   \
    const;                                                                       \
  template const std::vector<types::global_dof_index>                            \
    &TFETIDual<dim>::subdomain_dofs(const unsigned int) const;                   \
  template std::vector<unsigned int> TFETIDual<dim>::subdomains_per_process()    \
    const;                                                                       \
  template std::vector<unsigned int>                                             \
                        TFETIDual<dim>::subdomain_dofs_per_process() const;      \
  template unsigned int TFETIDual<dim>::n_subdomains_of_body(                    \
    const unsigned int) const;                                                   \
  template unsigned int         TFETIDual<dim>::n_primal_dofs() const;           \
  template unsigned int         TFETIDual<dim>::n_gluing_multipliers() const;    \
  template unsigned int         TFETIDual<dim>::n_dirichlet_multipliers() const; \
  template const CoarseProblem &TFETIDual<dim>::coarse_problem() const;          \
  template const ConstraintRows<dim> &TFETIDual<dim>::constraint_rows() const;   \
  template double TFETIDual<dim>::decomposition_time() const;                    \
  template double TFETIDual<dim>::max_interface_jump() const;                    \
  template double TFETIDual<dim>::relative_interface_jump() const;
    DUALCONTACT_INSTANTIATE(2)
    DUALCONTACT_INSTANTIATE(3)
#undef DUALCONTACT_INSTANTIATE
  } // namespace decomposition
} // namespace dualcontact
