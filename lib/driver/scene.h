#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <decomposition/decomposition_parameters.h>
#include <decomposition/distributed_mesh.h>
#include <driver/body_parameters.h>
#include <driver/contact_pair_parameters.h>
#include <driver/obstacle_parameters.h>
#include <fem/elastic_body.h>
#include <fem/stiffness_solver.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace driver
  {
    /**
     * Prepare @p solver for the stiffness matrix of @p body: a
     * fem::TrilinosSolver (mumps, amg) gets the body's locally owned dofs as
     * its rows and dim unknowns per node; other solvers need nothing.
     */
    template <int dim>
    void
    configure_solver(fem::StiffnessSolver        &solver,
                     const fem::ElasticBody<dim> &body);


    /**
     * The bodies of a scene and what is computed on each of them without
     * contact: the parameters of bodies, obstacles and contact pairs (read
     * and checked by the constructor, before anything is computed), the
     * meshes (checked against the parameters), the assembled systems, one
     * stiffness solve per body (scenes without contact pairs), and the
     * derived per-body results (energies, forces, reactions).
     *
     * Simulation drives the phases; ContactStage computes the displacements
     * instead of solve() when the scene has contact pairs; SimulationReport
     * writes what this class holds.  Each phase method appends lines for the
     * console to @p details.
     */
    template <int dim>
    class Scene
    {
    public:
      /** Per body: what was computed from the solution. */
      using BodyResults = typename fem::ElasticBody<dim>::Summary;

      /**
       * Read subsections `Discretization', `Body N', `Obstacle N', `Contact
       * pair N' of @p prm and make one stiffness solver per body
       * (`Stiffness solver').  Relative file names are looked up relative to
       * the folder of @p parameter_file too.
       */
      Scene(dealii::ParameterHandler &prm, const std::string &parameter_file);

      /** Mesh phase: build and check every body's mesh. */
      void
      create_meshes(std::vector<std::string> &details);
      /** Setup phase: dofs and constraints of every body. */
      void
      setup(std::vector<std::string> &details);
      /**
       * Assembly phase: K and f of every body (condensed), unless
       * @p global_systems is false (TFETI assembles each subdomain's own
       * K_s and f_s; the bodies' stiffness_matrix() and load_vector() are
       * then not available).
       */
      void
      assemble(std::vector<std::string> &details,
               const bool                global_systems = true);
      /**
       * The time of the load step to compute (driver::LoadSteps; 1, the
       * static problem, by default): every load expression is evaluated
       * at @p time, and the bodies' constraints get their prescribed values
       * at it (now, and in every later setup()).
       */
      void
      set_load_time(const double time);
      /** The time of set_load_time(). */
      double
      load_time() const
      {
        return load_time_;
      }
      /**
       * f of every body again at the load time (after assemble(); K and
       * the factorizations stay).  Bodies without an assembled system
       * (TFETI, assemble(details, false)) are left out: the TFETI dual
       * re-assembles its subdomains' loads.
       */
      void
      assemble_loads();
      /** Solve phase (no contact): u = K^{-1} f per body; @p factorize
       *  false: with the factorizations of the last call (a load step). */
      void
      solve(std::vector<std::string> &details, const bool factorize = true);
      /**
       * Postprocessing phase: BodyResults of every body; @p contact_forces
       * (per body, ContactStage::body_contact_forces()) enter the reactions
       * and the force balance, null for a scene without contact.
       */
      void
      postprocess(
        const std::vector<dealii::Vector<double>> *contact_forces = nullptr);
      /**
       * Refinement phase (ContactRefinement): drop the bodies (their dofs,
       * systems, displacements and results; a ContactStage must have let
       * go of them first, ContactStage::reset()) and refine every mesh by
       * its refine flags; setup() and the rest then run on the new meshes.
       */
      void
      refine(std::vector<std::string> &details);
      /**
       * Tell the stiffness solvers of the solve without contact where to
       * report a long factorization (fem::StiffnessSolver::set_monitor).
       */
      void
      set_solver_monitor(
        const std::function<void(const std::string &)> &monitor);
      /** Whether `Decomposition/Mesh distribution = distributed'. */
      bool
      has_distributed_meshes() const
      {
        return decomposition_.mesh_distribution ==
               decomposition::DecompositionParameters::MeshDistribution::
                 distributed;
      }
      /**
       * The bodies' distributed meshes under `Decomposition/Mesh
       * distribution = distributed' (after create_meshes()), else null.
       */
      const decomposition::DistributedMesh<dim> *
      distributed_mesh() const
      {
        return distributed_mesh_.get();
      }
      /** The mesh of body @p b (after create_meshes()), to flag cells. */
      dealii::Triangulation<dim> &
      triangulation(const unsigned int b)
      {
        return *triangulations_[b];
      }

      bool
      has_contact() const
      {
        return !pair_parameters_.empty();
      }
      unsigned int
      fe_degree() const
      {
        return fe_degree_;
      }
      unsigned int
      n_bodies() const
      {
        return body_parameters_.size();
      }
      const std::vector<BodyParameters<dim>> &
      body_parameters() const
      {
        return body_parameters_;
      }
      const std::vector<ContactPairParameters<dim>> &
      pair_parameters() const
      {
        return pair_parameters_;
      }
      /** The bodies (after setup()). */
      std::vector<const fem::ElasticBody<dim> *>
      bodies() const;
      /** The bodies as owned (for io::write_solution). */
      const std::vector<std::unique_ptr<fem::ElasticBody<dim>>> &
      elastic_bodies() const
      {
        return bodies_;
      }
      const fem::ElasticBody<dim> &
      body(const unsigned int b) const
      {
        return *bodies_[b];
      }
      /** Each body's stiffness solver (used by solve() only). */
      const fem::StiffnessSolver &
      solver(const unsigned int b) const
      {
        return *solvers_[b];
      }
      /** Per body the displacement (set by solve() or by contact). */
      std::vector<dealii::Vector<double>> &
      displacements()
      {
        return displacements_;
      }
      const std::vector<dealii::Vector<double>> &
      displacements() const
      {
        return displacements_;
      }
      const std::vector<BodyResults> &
      results() const
      {
        return results_;
      }

    private:
      /**
       * Throw before any mesh is made if the meshes and stiffness matrices
       * of all bodies (estimated from their coarse cells, refinements and
       * the element degree; a lower bound) would exceed @p memory_limit
       * [MB] (`Memory limit' in `subsection Dual problem', the one limit of
       * a scene): `Global refinements = 12' or huge subdivisions stop
       * with a message naming the parameters, instead of std::bad_alloc.
       */
      void
      check_size_estimate(const double memory_limit) const;
      /** The serial meshes of create_meshes() cut into subdomains and
       *  distributed (DistributedMesh); collective. */
      void
      distribute_meshes(std::vector<std::string> &details);

      unsigned int fe_degree_ = 1;
      /** See set_load_time(). */
      double load_time_ = 1.;
      /** Mapping degree of tractions on curved faces (ElasticBody). */
      unsigned int                            curved_load_mapping_degree_ = 4;
      std::vector<BodyParameters<dim>>        body_parameters_;
      std::vector<ObstacleParameters<dim>>    obstacle_parameters_;
      std::vector<ContactPairParameters<dim>> pair_parameters_;
      std::vector<std::shared_ptr<dealii::Triangulation<dim>>> triangulations_;
      /** `Decomposition/Mesh distribution' and the cut it needs. */
      decomposition::DecompositionParameters               decomposition_;
      std::unique_ptr<decomposition::DistributedMesh<dim>> distributed_mesh_;
      std::vector<std::unique_ptr<fem::ElasticBody<dim>>>  bodies_;
      std::vector<std::unique_ptr<fem::StiffnessSolver>>   solvers_;
      /**
       * Under MPI with `Solver = automatic': body @p b's cholmod copies on
       * this machine against `Decomposition/Memory limit'; beyond it the
       * body gets its mumps solver.  Returns what the log says of it (empty:
       * nothing changed).  Collective.
       */
      std::string
      choose_solver(const unsigned int b, const fem::ElasticBody<dim> &body);

      /** Under MPI with `Solver = automatic': a mumps solver per body, for
       *  a body whose cholmod copies would exceed factor_limit_ here. */
      std::vector<std::unique_ptr<fem::StiffnessSolver>> spread_solvers_;
      /** `Decomposition/Memory limit' [MB]. */
      double                              factor_limit_ = 8192;
      std::vector<dealii::Vector<double>> displacements_;
      std::vector<BodyResults>            results_;
    };
  } // namespace driver
} // namespace dualcontact
