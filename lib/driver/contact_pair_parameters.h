#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

#include <contact/contact_discretization.h>
#include <contact/contact_pair.h>
#include <driver/obstacle_parameters.h>

#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace driver
  {
    /**
     * One contact pair of a scene (subsection `Contact pair N'): a slave
     * surface (a boundary id of a body) whose nodes carry the contact
     * constraints, and a master, either a rigid obstacle (`Master = obstacle
     * K') or a boundary id of another body (`Master = body K'), with the
     * pair's friction law.
     *
     * parse_parameters() checks everything that does not need a mesh (the
     * bodies and obstacles exist, the friction values fit the law and the
     * dimension); check_mesh() checks the boundary ids once the meshes
     * exist.  Both run before anything is computed or written.
     */
    template <int dim>
    class ContactPairParameters
    {
    public:
      /** Declare the entries of `Contact pair N' in the current subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /**
       * Read the current subsection, whose path is @p path ("Contact pair
       * 1"), against a scene of @p n_bodies bodies and @p obstacles.
       */
      void
      parse_parameters(dealii::ParameterHandler                   &prm,
                       const std::string                          &path,
                       const unsigned int                          n_bodies,
                       const std::vector<ObstacleParameters<dim>> &obstacles);

      /**
       * The slave (and master) boundary id exist on the meshes of the slave
       * (and master) body; @p triangulations holds every body's mesh.
       */
      void
      check_mesh(const std::vector<std::shared_ptr<dealii::Triangulation<dim>>>
                   &triangulations) const;

      /** Whether body @p body (0-based) is the slave or master of the pair. */
      bool
      involves_body(const unsigned int body) const;

      /** The pair for contact::ContactDiscretization (bodies 0-based). */
      contact::ContactPair<dim> pair;
      /** "obstacle 1", "body 2": what the master is, for the log. */
      std::string master_description;
      /**
       * `Penetration tolerance' [-]: the deepest initial penetration of a
       * slave node into the master allowed, relative to the slave surface's
       * mesh size (check_initial_penetration()).
       */
      double penetration_tolerance = 0.25;

      /**
       * Throw, naming the pair, the node, its position and depth, if a slave
       * node of @p nodes (the pair's nodes among all pairs' nodes) lies
       * deeper inside the master than penetration_tolerance times the
       * slave surface's mesh size @p mesh_size [m]: the bodies overlap
       * before any load (a body placed inside another, or behind its
       * obstacle), which the small-displacement contact cannot undo.
       */
      void
      check_initial_penetration(
        const std::vector<contact::ContactNode<dim>> &nodes,
        const unsigned int                            pair_index,
        const double                                  mesh_size) const;

    private:
      std::string path_;
    };
  } // namespace driver
} // namespace dualcontact
