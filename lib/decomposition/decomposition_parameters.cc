#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <decomposition/decomposition_parameters.h>
#include <util/machine.h>

#include <cmath>

namespace dualcontact
{
  namespace decomposition
  {
    using namespace dealii;

    void
    DecompositionParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Decomposition");
      prm.declare_entry(
        "Method",
        "automatic",
        Patterns::Selection("automatic|none|tfeti"),
        "none: every body's stiffness matrix is factorized whole and the "
        "dual has the contact multipliers only. tfeti: total FETI, every "
        "body is cut into subdomains (`Partitioner'), each "
        "factorized on its own and floating, glued to its neighbours, held "
        "by its Dirichlet conditions and by contact through multipliers "
        "(free gluing and Dirichlet multipliers, the coarse problem G G' "
        "in SMALSE-M); under MPI every process assembles and factorizes "
        "only the subdomains it owns (the mesh replicated or distributed: "
        "`Mesh distribution'). "
        "automatic: the method estimated to finish first, from CHOLMOD's "
        "symbolic analyses of the whole bodies and of the subdomains TFETI "
        "would cut, before either is built (the log gives both estimates; "
        "doc/benchmarks/tfeti.md, \"Automatic choice\"), and tfeti "
        "whenever the undecomposed factors exceed `Memory limit'. Hanging "
        "nodes "
        "(local or contact refinement) are glued by multiplier rows.");
      prm.declare_entry(
        "Subdomains per body",
        "",
        Patterns::List(Patterns::Integer(1)),
        "Method = tfeti: the number of subdomains of each body (one number "
        "per body, or one for all bodies); empty: from `Cells per "
        "subdomain'. A part that METIS leaves in pieces (cells joined by "
        "an edge or a vertex only, or a refined cell beside a coarser one) "
        "becomes one subdomain per piece, so a body may get more.");
      prm.declare_entry(
        "Partitioner",
        "bisection",
        Patterns::Selection("metis|bisection"),
        "Method = tfeti: how a body's cells are cut into subdomains. metis: "
        "METIS on the graph of cells that share a face (fewest cut faces; "
        "the parts' boundaries may be jagged). bisection: recursive "
        "coordinate bisection of the cell centres, each cut across the "
        "longest extent of the cells it divides, at the quantile that "
        "gives both sides cells in proportion to their parts (box-shaped "
        "subdomains on a box). Either way a part in pieces becomes one "
        "subdomain per piece. Measured on the friction brick "
        "(doc/benchmarks/tfeti.md, \"Partitioner\"): METIS' parts cost "
        "12-50 times the Hessian products of bisection's from 24 "
        "subdomains on; equal on 3D Hertz and the 2D Coulomb block.");
      prm.declare_entry(
        "Gluing rows",
        "chain",
        Patterns::Selection("chain|orthonormal"),
        "Method = tfeti: the k - 1 rows that glue the k copies of a dof "
        "shared by k subdomains (non-redundant either way). chain: u_1 - "
        "u_2, u_2 - u_3, ... (entries 1 and -1). orthonormal: Helmert's "
        "rows (u_1 + ... + u_j - j u_{j+1}) / sqrt(j (j + 1)), the same "
        "space with B B' = I on the gluing rows of a dof. Measured on the "
        "friction brick (doc/benchmarks/tfeti.md, \"Gluing rows\"): "
        "orthonormal rows cost more Hessian products (level 20, 64 "
        "subdomains: 889 against 714) and more outer iterations.");
      prm.declare_entry(
        "Mesh distribution",
        "replicated",
        Patterns::Selection("replicated|distributed"),
        "Method = tfeti: where the meshes live. replicated: every process "
        "holds every body's whole mesh (under MPI a parallel::shared "
        "triangulation) and assembles its own subdomains from it. "
        "distributed: every process holds the cells of its own subdomains "
        "and one layer of ghost cells (a parallel::fullydistributed "
        "triangulation built from the serial description): no process "
        "keeps the whole mesh, and the contact search gathers the slave "
        "surfaces only (a slave node is placed on the master faces of "
        "whichever process has the closest). Needs `Method = tfeti' and at "
        "least one subdomain per process; not yet with `subsection Contact "
        "refinement' (it refines between solves).");
      prm.declare_entry("Cells per subdomain",
                        "1000",
                        Patterns::Integer(1),
                        "Method = tfeti without `Subdomains per body': each "
                        "body gets ceil(cells / this) subdomains. Measured "
                        "on the brick at 40 x 80 x 40 cells, 1e-6, two "
                        "processes (doc/benchmarks/tfeti.md, "
                        "\"Partitioner\"): 2,000 / 1,000 / 500 cells per "
                        "subdomain 1,165 / 979 / 1,894 Hessian products.");
      prm.declare_entry("Memory limit",
                        "8192",
                        Patterns::Double(0),
                        "Method = automatic: the largest estimated size [MB] "
                        "of the Cholesky factors of one body's stiffness "
                        "matrix on one machine for which the scene is not "
                        "decomposed (under MPI with a serial `Stiffness "
                        "solver/Solver' every process holds a copy: the "
                        "factor times the processes on the machine). Under "
                        "MPI with `Solver = automatic' it also decides a "
                        "body's solve outside the dual (a scene without "
                        "contact): cholmod on every process within it, mumps "
                        "beyond.");
      prm.leave_subsection();
    }


    void
    DecompositionParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Decomposition");
      const std::string name = prm.get("Method");
      method                 = name == "none"  ? Method::none :
                               name == "tfeti" ? Method::tfeti :
                                                 Method::automatic;
      partitioner            = prm.get("Partitioner") == "bisection" ?
                                 Partitioner::bisection :
                                 Partitioner::metis;
      gluing =
        prm.get("Gluing rows") == "chain" ? Gluing::chain : Gluing::orthonormal;
      subdomains_per_body.clear();
      for (const std::string &entry :
           Utilities::split_string_list(prm.get("Subdomains per body")))
        subdomains_per_body.push_back(Utilities::string_to_int(entry));
      mesh_distribution = prm.get("Mesh distribution") == "distributed" ?
                            MeshDistribution::distributed :
                            MeshDistribution::replicated;
      AssertThrow(mesh_distribution == MeshDistribution::replicated ||
                    method == Method::tfeti,
                  ExcMessage("`Mesh distribution = distributed' in "
                             "`subsection Decomposition' needs `Method = "
                             "tfeti' there: only TFETI's subdomains can live "
                             "on a distributed mesh."));
      cells_per_subdomain = prm.get_integer("Cells per subdomain");
      memory_limit        = prm.get_double("Memory limit");
      prm.leave_subsection();
    }


    unsigned int
    DecompositionParameters::n_subdomains(const unsigned int body,
                                          const unsigned int n_cells) const
    {
      const std::string where = "Body " + std::to_string(body + 1);
      if (subdomains_per_body.empty())
        return (n_cells + cells_per_subdomain - 1) / cells_per_subdomain;
      AssertThrow(subdomains_per_body.size() == 1 ||
                    body < subdomains_per_body.size(),
                  ExcMessage("`Subdomains per body' in `subsection "
                             "Decomposition' has " +
                             std::to_string(subdomains_per_body.size()) +
                             " entries, but there is a " + where +
                             ": give one number per body or one for all."));
      const unsigned int n = subdomains_per_body.size() == 1 ?
                               subdomains_per_body[0] :
                               subdomains_per_body[body];
      AssertThrow(n <= n_cells,
                  ExcMessage("`Subdomains per body' in `subsection "
                             "Decomposition' asks for " +
                             std::to_string(n) + " subdomains of " + where +
                             ", which has only " + std::to_string(n_cells) +
                             " cells."));
      return n;
    }


    DecompositionParameters::Method
    DecompositionParameters::resolve(const double factor_megabytes) const
    {
      if (method != Method::automatic)
        return method;
      // TFETI only where the global factor does not fit: under MPI too,
      // because without a dual preconditioner it needs thousands of
      // iterations where the undecomposed dual needs tens (the brick at
      // 10 x 20 x 10 on 2 processes: 104 s against 10 s,
      // doc/benchmarks/tfeti.md)
      return factor_megabytes > memory_limit ? Method::tfeti : Method::none;
    }


    double
    DecompositionParameters::estimate_factor_megabytes(const unsigned int dim,
                                                       const double n_dofs)
    {
      const double n_nodes = n_dofs / dim;
      const double nodes_in_factor =
        dim == 3 ? std::pow(n_nodes, 4. / 3.) :
                   n_nodes * std::log2(std::max(n_nodes, 2.));
      // a guess, not yet fitted (see the declaration)
      const double constant = dim == 3 ? 2.5 : 1.;
      return constant * nodes_in_factor * dim * dim * 8. / 1048576.;
    }


    double
    DecompositionParameters::factor_megabytes_on_machine(const unsigned int dim,
                                                         const double n_dofs,
                                                         const bool   spread)
    {
      const double copies = spread ? 1. : util::processes_on_this_machine();
      return copies * estimate_factor_megabytes(dim, n_dofs);
    }
  } // namespace decomposition
} // namespace dualcontact
