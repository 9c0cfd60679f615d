#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <fem/boundary_conditions.h>
#include <fem/cell_family.h>
#include <fem/isotropic_material.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace fem
  {
    class StiffnessSolver;

    /**
     * One linear elastic body: its mesh, finite element space (FE_Q of degree
     * 1 or 2 in each displacement component with the isoparametric mapping
     * on quadrilaterals and hexahedra, FE_SimplexP with the affine one on
     * triangles and tetrahedra: fem::CellFamily), material
     * regions, boundary conditions and loads, and the assembled stiffness
     * matrix K and load vector f.
     *
     * Tractions on faces that touch a curved manifold (the face's own
     * manifold or, in 3D, one of its edges', e.g. the flat top of a half
     * ball whose rim is a circle) are integrated with a mapping of degree
     * `curved_mapping_degree' (MappingQ, support points on the manifolds)
     * instead of the isoparametric one: with Q1 the loaded surface would
     * otherwise be the polygon of its chords and lose a fraction of the
     * load of order (h/R)^2 (2.55 % on the quarter ball of
     * inputs/hertz_3d.prm).  The stiffness keeps the isoparametric mapping.
     *
     * Dirichlet conditions and hanging nodes are built into K and f through
     * AffineConstraints (condensed: constrained rows and columns are
     * decoupled, with the inhomogeneities moved to f), so that K is SPD for a
     * body that is held, and a solution vector must go through distribute().
     *
     * The body knows nothing of contact and of other bodies: a scene holds
     * several of them, and K of the scene is block diagonal.
     */
    template <int dim>
    class ElasticBody
    {
    public:
      /**
       * @p name is used in messages ("Body 1").  @p materials maps every
       * material id present in the mesh to its material.
       */
      ElasticBody(const std::string                          &name,
                  std::shared_ptr<dealii::Triangulation<dim>> triangulation,
                  const unsigned int                          fe_degree,
                  const std::map<dealii::types::material_id, IsotropicMaterial>
                                    &materials,
                  const unsigned int curved_mapping_degree = 4);

      /**
       * Degree of the mapping on which the nominal traction resultants are
       * integrated (traction_resultants()), on faces that touch a curved
       * manifold: high enough that the resultant on the rim of a quarter
       * ball is exact far below the 0.1 % warning (degrees 6 and 8 agree to
       * 2e-13 relative on inputs/hertz_3d.prm and tests/app/two_bodies_3d,
       * whose exact resultants are known; degree 4, the default of the
       * assembly, is within 3e-11 there).
       */
      static constexpr unsigned int nominal_mapping_degree = 6;

      /** Resultant of one traction condition [N, N/m in 2D]. */
      struct TractionResultant
      {
        dealii::types::boundary_id boundary_id = 0;
        /**
         * int t ds over the exact surface (the faces mapped with degree
         * nominal_mapping_degree on the manifolds, Gauss quadrature of
         * nominal_mapping_degree + 2 points per direction): the load that
         * the input asks for.
         */
        dealii::Tensor<1, dim> nominal;
        /** The sum of this traction's entries of f, per component: the
         * load that the discrete model carries. */
        dealii::Tensor<1, dim> applied;
        /** |applied - nominal| / |nominal| (0 if nominal is 0) [-]. */
        double
        relative_difference() const
        {
          const double norm = nominal.norm();
          return norm > 0 ? (applied - nominal).norm() / norm : 0.;
        }
      };

      ~ElasticBody();

      void
      set_dirichlet_conditions(
        const std::vector<DirichletCondition<dim>> &conditions);
      void
      set_traction_conditions(
        const std::vector<TractionCondition<dim>> &conditions);
      /** Body force b [N/m^3] (dim components); none by default. */
      void
      set_body_force(std::shared_ptr<dealii::Function<dim>> body_force);

      /**
       * Distribute the degrees of freedom and build the constraints.
       * Throws if a cell has a material id without a material, or a
       * boundary condition names a boundary id that the mesh does not
       * have.
       */
      void
      setup();

      /**
       * Build the sparsity pattern and assemble K and f, condensed
       * (requires setup()).  Not needed by TFETI, which assembles each
       * subdomain's K_s and f_s with assemble_cells(): at 408,483 dofs the
       * global pattern and matrix are ~0.5 GB that no subdomain uses.
       */
      void
      assemble();

      /**
       * Evaluate every load (prescribed displacements, tractions, body
       * force) at @p time from now on (Function::set_time()), and, after
       * setup(), rebuild the constraints with the prescribed values at that
       * time: a load step (driver::LoadSteps).  K does not change.
       */
      void
      set_load_time(const double time);

      /**
       * Assemble f alone (after assemble()), at the loads' current time and
       * with the current constraints' inhomogeneities: the load of a step,
       * K and its factorizations kept.
       */
      void
      assemble_load();

      /** Whether assemble() was called since the last setup(). */
      bool
      is_assembled() const;

      /**
       * K_S and f_S of the cells @p cells alone, without any constraint (no
       * Dirichlet condition, no hanging node): the stiffness matrix and
       * load of a subdomain (decomposition::Subdomain), with the same cell
       * integrals as assemble().  @p dofs lists the dofs of these cells,
       * sorted; row i of the result belongs to dofs[i].  @p sparsity is
       * built here, @p matrix and @p load are initialized on it.
       */
      void
      assemble_cells(
        const std::vector<
          typename dealii::DoFHandler<dim>::active_cell_iterator> &cells,
        const std::vector<dealii::types::global_dof_index>        &dofs,
        dealii::SparsityPattern                                   &sparsity,
        dealii::SparseMatrix<double>                              &matrix,
        dealii::Vector<double>                                    &load) const;

      /**
       * Solve K u = f with @p solver and distribute; @p factorize false
       * reuses the solver's factorization of K (a later load step).
       */
      void
      solve(StiffnessSolver        &solver,
            dealii::Vector<double> &displacement,
            const bool              factorize = true) const;

      /** Set constrained entries of @p displacement from the constraints. */
      void
      distribute(dealii::Vector<double> &displacement) const;

      /**
       * What a solved body reports (results.txt, the log).  summarize()
       * computes all of it in one pass over the cells, assembling each
       * cell's K_c and f_c once: u_c' K_c u_c gives the energy and, minus
       * f_c, the residual whose sum over the supports is the reaction.  The
       * single-quantity functions below are that pass too; call summarize()
       * when more than one is needed.
       */
      struct Summary
      {
        /** 1/2 int eps(u) : C : eps(u) dx = 1/2 u' K u [J, J/m in 2D]. */
        double strain_energy = 0;
        /** f(u) = int b.u dx + int t.u ds [J, J/m in 2D]. */
        double external_work = 0;
        /** Resultant of body forces and tractions [N, N/m in 2D]. */
        dealii::Tensor<1, dim> applied_force;
        /** See reaction_forces() [N, N/m in 2D]. */
        std::map<dealii::types::boundary_id, dealii::Tensor<1, dim>>
          reaction_forces;
        /**
         * Resultant of the contact forces on the body [N, N/m in 2D] (zero
         * unless summarize() was given them).
         */
        dealii::Tensor<1, dim> contact_force;
        /**
         * |applied + sum of reactions + contact| over the largest of those
         * forces: zero for a body in equilibrium (round-off and the solve's
         * accuracy); 0 when no force acts.
         */
        double force_imbalance = 0;
        /** Largest nodal displacement magnitude [m]. */
        double max_displacement = 0;
        /** See traction_resultants(), one per traction condition. */
        std::vector<TractionResultant> traction_resultants;
      };

      /**
       * All of Summary for @p displacement, in one pass over the cells.
       * @p contact_force: the nodal forces the contact exerts on the body
       * (its dofs, unconstrained numbering; contact::ContactDiscretization::
       * nodal_contact_forces()), or null for a body without contact.  The
       * reactions are the residual K_full u - f_full - f_contact condensed
       * through the hanging-node constraints (r = C' r_full), summed over
       * the prescribed dofs of each support: the contact force at a
       * prescribed dof is not the support's.
       */
      Summary
      summarize(const dealii::Vector<double> &displacement,
                const dealii::Vector<double> *contact_force = nullptr) const;

      /** Strain energy 1/2 int eps(u) : C : eps(u) dx [J, J/m in 2D]. */
      double
      strain_energy(const dealii::Vector<double> &displacement) const;

      /** Work of the applied loads f(u) = int b.u dx + int t.u ds [J]. */
      double
      external_work(const dealii::Vector<double> &displacement) const;

      /**
       * Reaction force [N, N/m in 2D] on each boundary id carrying a Dirichlet
       * condition: the sum over its support dofs of the residual
       * K_full u - f_full of the unconstrained system, i.e. the force that the
       * support exerts on the body.
       */
      std::map<dealii::types::boundary_id, dealii::Tensor<1, dim>>
      reaction_forces(const dealii::Vector<double> &displacement) const;

      /** Resultant of body forces and tractions [N, N/m in 2D]. */
      dealii::Tensor<1, dim>
      applied_force() const;

      /** Largest nodal displacement magnitude [m]. */
      double
      max_displacement(const dealii::Vector<double> &displacement) const;

      /**
       * Per traction condition (in their order), the nominal resultant
       * (integrated on the exact surface) and the applied one (what f
       * carries); they differ where the assembly's mapping does not follow
       * the geometry.
       */
      std::vector<TractionResultant>
      traction_resultants() const;

      const std::string &
      name() const;
      const dealii::Triangulation<dim> &
      triangulation() const;
      const dealii::DoFHandler<dim> &
      dof_handler() const;
      const dealii::FESystem<dim> &
      fe() const;
      const dealii::Mapping<dim> &
      mapping() const;
      /** The kind of cells of the mesh, and what goes with it. */
      const CellFamily<dim> &
      cell_family() const;
      const dealii::AffineConstraints<double> &
      constraints() const;
      /**
       * The hanging-node constraints alone (closed, homogeneous; no
       * Dirichlet condition merged in): what joins the refined cells to
       * the coarse ones, for TFETI's subdomains and the contact sides.
       */
      const dealii::AffineConstraints<double> &
      hanging_node_constraints() const;
      const dealii::SparseMatrix<double> &
      stiffness_matrix() const;
      const dealii::Vector<double> &
      load_vector() const;
      const IsotropicMaterial &
      material(const dealii::types::material_id id) const;
      unsigned int
      n_dofs() const;

      /**
       * Whether the mesh is distributed (a parallel::fullydistributed
       * triangulation of TFETI's `Mesh distribution = distributed'): each
       * process has its own cells and a layer of ghosts, summarize() sums
       * the owned cells over the processes (collective), and the lines of
       * constraints() and hanging_node_constraints() are those of every
       * dof (gathered: hanging and prescribed dofs, a surface's worth).
       */
      bool
      is_distributed() const;
      /** The mesh's communicator (MPI_COMM_SELF for a serial mesh). */
      MPI_Comm
      communicator() const;

    private:
      /** Whether this process adds @p cell to sums over the mesh: every
       *  cell of a replicated mesh, the owned ones of a distributed one. */
      bool
      is_counted_here(
        const typename dealii::DoFHandler<dim>::active_cell_iterator &cell)
        const;
      /** Whether this process counts @p dof in sums over dofs. */
      bool
      is_owned_dof(const dealii::types::global_dof_index dof) const;
      /** Adds the hanging-node lines (@p hanging) or the Dirichlet lines
       *  of the dofs other processes own (a distributed mesh). */
      void
      gather_constraint_lines(const bool hanging);
      /** @p residual (all dofs) condensed through the hanging-node
       *  constraints: each hanging dof's entry moved to its parents. */
      void
      condense_hanging_nodes(dealii::Vector<double> &residual) const;
      /** Summary::force_imbalance of @p summary's forces. */
      static double
      force_imbalance(const Summary &summary);

      /** The hanging-node and Dirichlet constraints (setup(), and again
       *  for the prescribed values of a new load time). */
      void
      make_constraints();
      /** FEValues and buffers reused over the cells of one loop. */
      struct CellScratch;

      /**
       * Whether the face follows a curved manifold: its own or, in 3D, one
       * of its edges' manifold id is not the flat one.
       */
      static bool
      touches_curved_manifold(
        const typename dealii::Triangulation<dim>::face_iterator &face);

      /**
       * The face values on which the traction of face @p f of @p cell is
       * integrated (reinitialized): the curved mapping's where the face
       * touches a curved manifold and that mapping has a higher degree than
       * the isoparametric one, else the isoparametric mapping's.
       */
      const dealii::FEFaceValues<dim> &
      traction_face_values(
        const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
        const unsigned int                                            f,
        CellScratch &scratch) const;

      /** Local matrix and load of one cell (both unconstrained). */
      void
      cell_system(
        const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
        CellScratch                                                  &scratch,
        dealii::FullMatrix<double> &cell_matrix,
        dealii::Vector<double>     &cell_rhs) const;

      /** traction_resultants() with the face values of @p scratch. */
      std::vector<TractionResultant>
      traction_resultants(CellScratch &scratch) const;

      std::string                                             name_;
      std::shared_ptr<dealii::Triangulation<dim>>             triangulation_;
      CellFamily<dim>                                         cell_family_;
      dealii::FESystem<dim>                                   fe_;
      unsigned int                                            mapping_degree_;
      // of the curved loaded faces; equal to mapping_degree_ on simplices
      unsigned int                                curved_mapping_degree_;
      std::unique_ptr<const dealii::Mapping<dim>> mapping_;
      // null unless curved_mapping_degree_ > mapping_degree_
      std::unique_ptr<const dealii::Mapping<dim>> curved_mapping_;
      dealii::DoFHandler<dim>                                 dof_handler_;
      std::map<dealii::types::material_id, IsotropicMaterial> materials_;
      std::vector<DirichletCondition<dim>>                    dirichlet_;
      std::vector<TractionCondition<dim>>                     tractions_;
      std::shared_ptr<dealii::Function<dim>>                  body_force_;
      dealii::AffineConstraints<double>                       constraints_;
      dealii::AffineConstraints<double> hanging_node_constraints_;
      dealii::SparsityPattern           sparsity_;
      dealii::SparseMatrix<double>      stiffness_;
      dealii::Vector<double>            load_;
    };
  } // namespace fem
} // namespace dualcontact
