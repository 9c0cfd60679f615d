#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * Whether and how the bodies of a scene are cut into subdomains
     * (subsection `Decomposition').
     */
    struct DecompositionParameters
    {
      enum class Method
      {
        /** tfeti when the global factor exceeds the memory limit; else
         *  none (see resolve()) */
        automatic,
        /** the undecomposed dual (contact::DualProblem) */
        none,
        /** total FETI (TFETIDual) */
        tfeti
      };
      Method method = Method::automatic;
      /**
       * Subdomains of each body (one entry per body, or one for all);
       * empty: from cells_per_subdomain.
       */
      std::vector<unsigned int> subdomains_per_body;
      /** How the cells of a body are cut into subdomains. */
      enum class Partitioner
      {
        /** METIS on the graph of cells that share a face */
        metis,
        /** recursive coordinate bisection of the cell centres (each cut
         *  across the longest extent, at the quantile of the parts on
         *  either side) */
        bisection
      };
      Partitioner partitioner = Partitioner::bisection;
      /** The rows that glue the copies of a dof shared by k subdomains. */
      enum class Gluing
      {
        /** k - 1 rows u_j - u_{j+1} = 0 through the copies in subdomain
         *  order (entries +1, -1) */
        chain,
        /** k - 1 orthonormal rows spanning the same space (Helmert's:
         *  row j = (u_1 + ... + u_j - j u_{j+1}) / sqrt(j (j + 1))), so
         *  that B B' = I on the gluing rows of a dof */
        orthonormal
      };
      Gluing gluing = Gluing::chain;
      /** Where the bodies' meshes live under TFETI. */
      enum class MeshDistribution
      {
        /** every process holds the whole mesh (parallel::shared under
         *  MPI) */
        replicated,
        /** every process holds the cells of its own subdomains and a
         *  layer of ghosts (DistributedMesh, parallel::fullydistributed) */
        distributed
      };
      MeshDistribution mesh_distribution = MeshDistribution::replicated;
      /** Target number of cells per subdomain when no count is given. */
      unsigned int cells_per_subdomain = 1000;
      /**
       * Limit [MB] of the estimated Cholesky factor of the whole stiffness
       * matrix for `automatic' (estimate_factor_megabytes()).
       */
      double memory_limit = 8192;
      /**
       * The preconditioner TFETIDual builds and supplies to the QP:
       * "lumped", "dirichlet" (the interface Schur complements of the
       * subdomains, one more factorization each) or anything else for
       * none.  Not a parameter of this subsection: the driver copies
       * `QP solver/Preconditioner'.
       */
      std::string preconditioner = "none";
      /**
       * Whether the QP runs on distributed multipliers (each on the
       * process of its subdomain, TFETIDual, "Processes") rather than on
       * replicated ones.  Not a parameter of this subsection: the driver
       * resolves `Dual problem/QP vectors'.
       */
      bool distributed_multipliers = false;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /**
       * The number of subdomains of body @p body (0-based) of @p n_cells
       * active cells; throws, naming the parameter, when it exceeds the
       * cells.
       */
      unsigned int
      n_subdomains(const unsigned int body, const unsigned int n_cells) const;

      /**
       * The method `automatic' stands for: tfeti when the estimated factors
       * on this machine (@p factor_megabytes: the factor times its copies,
       * one per process here with a serial solver) exceed memory_limit, on
       * any number of
       * processes; none otherwise (also under MPI: without a dual
       * preconditioner TFETI is slower than the undecomposed dual where
       * that fits).
       */
      Method
      resolve(const double factor_megabytes) const;

      /**
       * An estimate [MB] of the nonzeros of the sparse Cholesky factor of a
       * 3D (2D) stiffness matrix with @p n_dofs dofs and @p dofs_per_node
       * components under nested dissection: 3D n^(4/3), 2D n log2 n
       * (n the nodes), times dofs_per_node^2 entries of 8 bytes, times a
       * constant (2.5 in 3D, 1 in 2D) that is a guess, not yet fitted to
       * CHOLMOD's measured factor sizes.
       */
      static double
      estimate_factor_megabytes(const unsigned int dim, const double n_dofs);

      /**
       * What the factor of a body of @p n_dofs weighs on this machine [MB]:
       * estimate_factor_megabytes() times its copies, one for a solver
       * that spreads its factor over the processes (@p spread: mumps,
       * amg), one per process of this machine for a serial one (cholmod,
       * umfpack: every process holds the whole factor).  The quantity that
       * `Memory limit' bounds, both for the choice of TFETI (resolve()) and
       * for the stiffness solver of a scene without contact.
       */
      static double
      factor_megabytes_on_machine(const unsigned int dim,
                                  const double       n_dofs,
                                  const bool         spread);
    };
  } // namespace decomposition
} // namespace dualcontact
