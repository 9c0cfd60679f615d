#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

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

    private:
      std::string path_;
    };
  } // namespace driver
} // namespace dualcontact
