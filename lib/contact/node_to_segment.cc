#include <deal.II/base/mpi.h>
#include <deal.II/fe/mapping.h>

#include <contact/node_to_segment.h>
#include <util/machine.h>

#include <cmath>
#include <limits>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    NodeToSegment<dim>::NodeToSegment(
      const ContactPair<dim>                           &pair,
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const MasterSurface<dim>                         *surface,
      const std::vector<Point<dim>>                    &positions)
        : pair_(pair)
        , master_(pair.obstacle ? nullptr : bodies.at(pair.master_body))
        , surface_(surface)
    {
      Assert(pair.obstacle || surface != nullptr, ExcInternalError());
      if (master_ != nullptr && master_->is_distributed())
        place_on_distributed_master(positions);
    }


    template <int dim>
    bool
    NodeToSegment<dim>::place(const unsigned int i,
                              ContactNode<dim>  &node,
                              MasterEntries     &master) const
    {
      if (pair_.obstacle)
      {
        Tensor<1, dim> outward;
        pair_.obstacle->project(node.position, node.master_point, outward);
        node.normal = -outward;
        return (node.position - node.master_point).norm() <=
               pair_.search_distance;
      }
      if (!master_->is_distributed())
        return place_on_master_body(node, master);
      AssertIndexRange(i, placements_.size());
      const Placement &placement = placements_[i];
      if (!placement.found)
        return false;
      node.master_point = placement.master_point;
      node.normal       = placement.normal;
      master            = placement.entries;
      return true;
    }


    /*
     * The closest point over the master faces, the node's normal (minus
     * the master cell's outward normal there) and the master's shape
     * functions at that point.
     */
    template <int dim>
    bool
    NodeToSegment<dim>::place_on_master_body(
      ContactNode<dim> &node,
      MasterEntries    &master_entries) const
    {
      const typename MasterSurface<dim>::Projection projection =
        surface_->closest_face(node.position);
      node.master_point = projection.point;
      if (std::sqrt(projection.distance_square) > pair_.search_distance)
        return false;
      node.normal = -projection.outward_normal;

      const typename MasterSurface<dim>::Face &face =
        surface_->face(projection.face);
      const Point<dim> unit =
        master_->cell_family().unit_point(master_->mapping(),
                                          face.cell,
                                          node.master_point);
      std::vector<types::global_dof_index> master_dofs(
        master_->fe().n_dofs_per_cell());
      face.cell->get_dof_indices(master_dofs);
      for (unsigned int k = 0; k < master_->fe().n_dofs_per_cell(); ++k)
      {
        const double phi = master_->fe().shape_value(k, unit);
        if (std::abs(phi) > 1e-14)
        {
          master_entries.entries.push_back(
            {pair_.master_body, master_dofs[k], phi});
          master_entries.components.push_back(
            master_->fe().system_to_component_index(k).first);
        }
      }
      return true;
    }


    template <int dim>
    void
    NodeToSegment<dim>::place_on_distributed_master(
      const std::vector<Point<dim>> &positions)
    {
      const MPI_Comm     comm = master_->communicator();
      const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
      struct Closest
      {
        double distance_square;
        int    rank;
      };
      std::vector<Closest> closest(positions.size());
      for (unsigned int i = 0; i < positions.size(); ++i)
        closest[i] = {surface_->n_faces() > 0 ?
                        surface_->closest_face(positions[i]).distance_square :
                        std::numeric_limits<double>::max(),
                      static_cast<int>(rank)};
      const int ierr = MPI_Allreduce(MPI_IN_PLACE,
                                     closest.data(),
                                     closest.size(),
                                     MPI_DOUBLE_INT,
                                     MPI_MINLOC,
                                     comm);
      AssertThrowMPI(ierr);

      // the won nodes: (node, found, master point, normal, entries)
      std::vector<double> local;
      for (unsigned int i = 0; i < positions.size(); ++i)
        if (closest[i].rank == static_cast<int>(rank) &&
            surface_->n_faces() > 0)
        {
          ContactNode<dim> node;
          node.position = positions[i];
          MasterEntries entries;
          const bool    found = place_on_master_body(node, entries);
          local.push_back(i);
          local.push_back(found ? 1 : 0);
          for (unsigned int d = 0; d < dim; ++d)
            local.push_back(node.master_point[d]);
          for (unsigned int d = 0; d < dim; ++d)
            local.push_back(node.normal[d]);
          local.push_back(entries.entries.size());
          for (unsigned int e = 0; e < entries.entries.size(); ++e)
          {
            local.push_back(entries.entries[e].dof);
            local.push_back(entries.entries[e].value);
            local.push_back(entries.components[e]);
          }
        }
      const std::vector<double> all =
        util::concatenate_over_processes(local, comm);
      placements_.assign(positions.size(), Placement());
      for (std::size_t k = 0; k < all.size();)
      {
        Placement &placement = placements_[static_cast<unsigned int>(all[k++])];
        placement.found      = all[k++] > 0;
        for (unsigned int d = 0; d < dim; ++d)
          placement.master_point[d] = all[k++];
        for (unsigned int d = 0; d < dim; ++d)
          placement.normal[d] = all[k++];
        const std::size_t n_entries = all[k++];
        for (std::size_t e = 0; e < n_entries; ++e, k += 3)
        {
          placement.entries.entries.push_back(
            {pair_.master_body,
             static_cast<types::global_dof_index>(all[k]),
             all[k + 1]});
          placement.entries.components.push_back(
            static_cast<unsigned int>(all[k + 2]));
        }
      }
    }


    template class NodeToSegment<2>;
    template class NodeToSegment<3>;
  } // namespace contact
} // namespace dualcontact
