#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

#include <driver/scene_layout.h>
#include <fem/boundary_conditions.h>
#include <fem/isotropic_material.h>
#include <io/mesh_generator.h>
#include <io/placement.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace driver
  {
    /**
     * Everything the parameter file says about one body (subsection
     * `Body N'): its mesh (subsection `Mesh', io::MeshGenerator), placement
     * (subsection `Placement', io::Placement), material regions
     * (`Number of materials' subsections `Material 1', ...), prescribed
     * displacements (`Number of Dirichlet conditions' subsections
     * `Dirichlet 1', ...), surface tractions (`Number of traction
     * conditions' subsections `Traction 1', ...) and the body force.
     *
     * `Dirichlet 1' and `Traction 1' are always declared (so that
     * --print-parameters documents them); they are used only if the
     * corresponding number is at least 1, and setting them while the number
     * is 0 is an error.
     */
    template <int dim>
    class BodyParameters
    {
    public:
      /** Declare the `Number of ...' entries in the current subsection. */
      static void
      declare_layout_entries(dealii::ParameterHandler &prm);

      /** Read the `Number of ...' entries of the current subsection. */
      static BodyLayout
      parse_layout(dealii::ParameterHandler &prm);

      /** Declare all entries of a body with @p layout (current subsection). */
      static void
      declare_parameters(dealii::ParameterHandler &prm,
                         const BodyLayout         &layout);

      /**
       * Read the current subsection, whose path is @p path ("Body 1"); the
       * body is called @p name in messages.  Checks every value, and that
       * files named exist.
       */
      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &path,
                       const std::string        &parameter_file_folder);

      /**
       * Check the parameters against the body's mesh: every boundary id of a
       * Dirichlet or traction condition exists on the boundary, every
       * material id of a cell has a material, and a body without Dirichlet
       * condition is held by contact (@p in_contact: the body is the slave
       * or master of a contact pair; its rigid-body modes then go into the
       * dual problem's equality constraints).
       */
      void
      check_mesh(const dealii::Triangulation<dim> &triangulation,
                 const bool                        in_contact) const;

      std::string                                                  name;
      io::MeshGenerator<dim>                                       mesh;
      io::Placement<dim>                                           placement;
      std::map<dealii::types::material_id, fem::IsotropicMaterial> materials;
      std::vector<fem::DirichletCondition<dim>>                    dirichlet;
      std::vector<fem::TractionCondition<dim>>                     tractions;
      std::shared_ptr<dealii::Function<dim>>                       body_force;
      /** Whether `Body force' is not identically "0; 0(; 0)". */
      bool has_body_force = false;

    private:
      std::string              path_;
      std::vector<std::string> dirichlet_paths_;
      std::vector<std::string> traction_paths_;
    };
  } // namespace driver
} // namespace dualcontact
