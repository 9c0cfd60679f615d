#pragma once

#include <deal.II/base/parameter_handler.h>

#include <driver/contact_stage.h>
#include <driver/scene.h>

#include <string>
#include <utility>
#include <vector>

namespace dualcontact
{
  namespace driver
  {
    /**
     * Contact-zone adaptive refinement (subsection `Contact refinement'):
     * after a solve, mark the cells where the contact solution needs a finer
     * mesh, refine them, and let Simulation solve again on the refined
     * meshes, `Cycles' times.
     *
     * Why the contact zone: the error of a contact solution concentrates at
     * the contact zone, above all at its edge, where the pressure has a
     * square-root singularity (Hertz) and the discrete edge can only lie
     * between two nodes; away from it the displacement is smooth and a
     * coarse mesh is as accurate.  Uniform refinement spends most of its
     * dofs where nothing needs them (doc/hertz.md, "Contact-zone
     * refinement", measures how many).
     *
     * What is marked, on the pairs selected by `Pairs':
     * - every cell of the slave body that has a dof of a contact node in
     *   contact (not separated by the `Contact status tolerance') or with a
     *   gap after the solve below `Gap threshold' [m] (where the zone may
     *   grow), and every cell within `Zone factor' times the size of the
     *   marked zone of such a node: the stresses under a contact zone vary
     *   over a depth of the zone's size; refining only the cells at the
     *   surface makes a fine skin over a coarse body, and the pressure
     *   stops converging (measured on Hertz 2D: the peak pressure error
     *   grows to +3 % while the surface h halves 6 times);
     * - for a body-body pair, the master body's cell around the closest
     *   master point of each such node (the master surface must resolve the
     *   slave's pressure too);
     * - optionally (`Indicator fraction' > 0) the given fraction of cells
     *   of every body of a selected pair with the largest Kelly error
     *   indicator of the displacement (jumps of the normal derivative
     *   across faces): the far field where the stresses vary.
     * No cell beyond `Maximum level' is refined; the loop stops early once
     * the scene has `Maximum dofs' dofs.  Hanging nodes: the bodies'
     * AffineConstraints hold them (fem::ElasticBody), the contact
     * discretization condenses master-side hanging nodes through them and
     * drops slave-side hanging nodes as contact nodes, their area weights
     * going to the parent nodes (contact::ContactDiscretization).
     *
     * Everything is computed identically on every process (the meshes are
     * shared, the Kelly indicator is summed over the processes' cells), so
     * the processes refine alike.
     */
    template <int dim>
    class ContactRefinement
    {
    public:
      /** One solve of the loop: what results.txt / statistics.json record. */
      struct CycleRecord
      {
        unsigned int              cycle = 0;
        std::vector<unsigned int> n_cells; ///< per body
        std::vector<unsigned int> n_dofs;  ///< per body
        unsigned int              n_contact_nodes = 0;
        unsigned int              n_in_contact    = 0; ///< not separated
        /** Cells refined for the next cycle (all bodies; 0 in the last). */
        unsigned int n_marked_cells = 0;
        /**
         * Per body the bounding box (lower, upper corner) of the vertices of
         * the cells refined for the next cycle, hanging-node balance
         * included; lower > upper when none.  Shows where the loop refines.
         */
        std::vector<std::pair<dealii::Point<dim>, dealii::Point<dim>>>
          marked_box;
        /**
         * The same for the cells the contact zone criteria flagged (nodes,
         * gap threshold, zone factor), before the error indicator and the
         * balance add theirs.
         */
        unsigned int n_zone_cells = 0;
        std::vector<std::pair<dealii::Point<dim>, dealii::Point<dim>>> zone_box;
        /** Per pair: contact nodes, in contact, normal force, max pressure. */
        std::vector<unsigned int> pair_nodes, pair_in_contact;
        std::vector<double>       pair_normal_force, pair_max_pressure;
        unsigned int              qp_iterations       = 0;
        unsigned int              qp_hessian_products = 0;
        double                    wall_time           = 0; ///< [s], the cycle
      };

      /** Declare subsection `Contact refinement'. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /**
       * Read and check the subsection (pair numbers against @p n_pairs;
       * cycles without contact pairs are an error).
       */
      ContactRefinement(dealii::ParameterHandler &prm,
                        const unsigned int        n_pairs);

      /** Number of refinement cycles (0: off). */
      unsigned int
      n_cycles() const
      {
        return n_cycles_;
      }
      /** `Maximum dofs' (0: no limit). */
      unsigned int
      max_dofs() const
      {
        return max_dofs_;
      }

      /**
       * The record of the solve just done (cycle @p cycle, wall time
       * @p wall_time [s]); n_marked_cells is set by mark().
       */
      CycleRecord
      record(const unsigned int       cycle,
             const Scene<dim>        &scene,
             const ContactStage<dim> &contact,
             const double             wall_time) const;

      /**
       * Set the refine flags of the bodies' meshes from the solution of
       * @p scene and @p contact (see the class documentation), with the
       * flags the one-hanging-node balance adds, and record their number
       * and bounding boxes in @p record.  Refining is Scene::refine().
       */
      void
      mark(Scene<dim>              &scene,
           const ContactStage<dim> &contact,
           CycleRecord             &record) const;

      /**
       * Throw, before any solve, where a selected body's mesh cannot be
       * refined as asked: tetrahedra (no hanging nodes in deal.II 9.4) and,
       * with `Indicator fraction' > 0, any simplex mesh (deal.II 9.4's
       * KellyErrorEstimator has no simplex faces).  Nothing to check
       * without cycles.
       */
      void
      check_meshes(const Scene<dim> &scene) const;

      /** The pairs' numbers as written (`all' or a list), for the log. */
      std::string
      description() const;

    private:
      unsigned int n_cycles_ = 0;
      /** Selected pairs, 0-based; every pair if `Pairs = all'. */
      std::vector<unsigned int> pairs_;
      bool                      all_pairs_          = true;
      double                    gap_threshold_      = 0;
      double                    zone_factor_        = 0.25;
      double                    indicator_fraction_ = 0;
      unsigned int              max_level_          = 0;
      unsigned int              max_dofs_           = 0;
    };
  } // namespace driver
} // namespace dualcontact
