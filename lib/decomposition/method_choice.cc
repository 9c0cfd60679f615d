#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <decomposition/cell_partition.h>
#include <decomposition/method_choice.h>
#include <fem/factor_estimate.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace dualcontact
{
  namespace decomposition
  {
    using namespace dealii;

    namespace
    {
      // Fitted to the runs of doc/benchmarks/tfeti.md, "Automatic choice"
      // (2 cores, OpenBLAS, one thread a process, idle machine).

      /** The undecomposed factorization orders the contact dofs last (the
       * Schur block that F is made from): on the brick at 20 x 40 x 20 it
       * took 87.6 GFlop and 4.57e7 nonzeros where the analysis of the
       * pattern alone gives 44.9 GFlop and 3.5e7. */
      constexpr double schur_flop_factor    = 1.95;
      constexpr double schur_nonzero_factor = 1.3;
      /** The whole-body factorization's rate [flop/s] grows with its size
       * (larger supernodes): 16 GFlop/s at 87.6 GFlop (level 20), 28.8
       * GFlop/s at 5,470 GFlop (level 40); a power law through both,
       * at most 30 GFlop/s. */
      double
      global_rate(const double flops)
      {
        return std::min(3e10, 1.6e10 * std::pow(flops / 8.76e10, 0.142));
      }
      /** The rest of the undecomposed set-up (the Schur factor's dense
       * trailing block, F = W'W) on top of the factorization. */
      constexpr double undecomposed_overhead = 1.25;
      /** Subdomain factorizations [flop/s] (small supernodes): the level-40
       * brick's 128 subdomains, 32 GFlop, in 3.3 s on 2 processes. */
      constexpr double subdomain_rate = 5e9;
      /** A product of F: a forward and backward solve with every
       * subdomain's factor and the product's other work (B, B', the coarse
       * projector), memory-bound [s per factor nonzero]: 147 ms a product
       * for the 1.09e8 nonzeros of the level-40 brick's 128 subdomains on
       * one process. */
      constexpr double solve_seconds_per_nonzero = 1.35e-9;
      /** Products before the QP: the Lanczos estimates of lambda_max(F)
       * and lambda_max(PFP), about 30 each. */
      constexpr double setup_products = 60;


      /** The stiffness pattern of the cells @p cells of @p body on their
       * own dofs, in the order of the body's numbering (no constraints). */
      template <int dim>
      SparsityPattern
      cells_pattern(
        const fem::ElasticBody<dim> &body,
        const std::vector<typename DoFHandler<dim>::active_cell_iterator>
          &cells)
      {
        std::vector<types::global_dof_index> dofs;
        std::vector<types::global_dof_index> cell_dofs(
          body.fe().n_dofs_per_cell());
        for (const auto &cell : cells)
        {
          cell->get_dof_indices(cell_dofs);
          dofs.insert(dofs.end(), cell_dofs.begin(), cell_dofs.end());
        }
        std::sort(dofs.begin(), dofs.end());
        dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
        DynamicSparsityPattern               dsp(dofs.size());
        std::vector<types::global_dof_index> local(cell_dofs.size());
        for (const auto &cell : cells)
        {
          cell->get_dof_indices(cell_dofs);
          for (unsigned int k = 0; k < cell_dofs.size(); ++k)
            local[k] =
              std::lower_bound(dofs.begin(), dofs.end(), cell_dofs[k]) -
              dofs.begin();
          for (const auto i : local)
            for (const auto j : local)
              dsp.add(i, j);
        }
        SparsityPattern pattern;
        pattern.copy_from(dsp);
        return pattern;
      }
    } // namespace


    template <int dim>
    MethodChoice<dim>::MethodChoice(
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const DecompositionParameters                    &parameters,
      const double                                      tolerance,
      const unsigned int                                n_processes,
      const unsigned int                                processes_on_machine,
      const bool                                        spread_factor)
        : method_(parameters.method)
        , memory_limit_(parameters.memory_limit)
    {
      if (parameters.method != DecompositionParameters::Method::automatic)
        return;
      double rough = 0;
      for (const auto *body : bodies)
        rough +=
          DecompositionParameters::factor_megabytes_on_machine(dim,
                                                               body->n_dofs(),
                                                               spread_factor);
      if (rough > 4 * memory_limit_)
      {
        method_ = DecompositionParameters::Method::tfeti;
        reason_ = "the factors estimated from the dof counts (" +
                  std::to_string(static_cast<long>(rough)) +
                  " MB) exceed 4 x `Memory limit'";
        return;
      }
      // the same answer on every process: the first one's (the analyses
      // are deterministic, but a tie must not split the processes)
      estimate_undecomposed(bodies, processes_on_machine, spread_factor);
      estimate_tfeti(bodies, parameters, tolerance, n_processes);
      const bool fits = undecomposed_.megabytes <= memory_limit_;
      method_         = fits && undecomposed_.seconds() <= tfeti_.seconds() ?
                          DecompositionParameters::Method::none :
                          DecompositionParameters::Method::tfeti;
      reason_ = !fits ? "the undecomposed factors exceed `Memory limit'" :
                        "the shorter estimate";
      if (Utilities::MPI::job_supports_mpi() && n_processes > 1)
        method_ = Utilities::MPI::broadcast(MPI_COMM_WORLD, method_, 0);
    }


    template <int dim>
    void
    MethodChoice<dim>::estimate_undecomposed(
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const unsigned int                                processes_on_machine,
      const bool                                        spread_factor)
    {
      for (const auto *body : bodies)
      {
        // every cell, not DoFTools' locally owned ones (a shared mesh
        // under MPI), and no constraints (not all known on every process):
        // the prescribed dofs stay in, a little more fill than the
        // condensed matrix has
        std::vector<typename DoFHandler<dim>::active_cell_iterator> cells;
        for (const auto &cell : body->dof_handler().active_cell_iterators())
          cells.push_back(cell);
        const SparsityPattern             pattern = cells_pattern(*body, cells);
        const fem::FactorEstimate::Result result =
          fem::FactorEstimate::analyze(pattern,
                                       fem::CholmodSolver::Ordering::automatic);
        undecomposed_.factor_flops += result.flops;
        undecomposed_.factor_nonzeros += result.factor_nonzeros;
      }
      undecomposed_.computed = true;
      const double flops     = schur_flop_factor * undecomposed_.factor_flops;
      undecomposed_.setup_seconds =
        undecomposed_overhead * flops / global_rate(flops);
      // the dual's products are dense (F assembled: m^2 flops), a few
      // hundred at most: well under a second where the choice is close
      undecomposed_.qp_seconds = 0;
      undecomposed_.megabytes  = 8e-6 * schur_nonzero_factor *
                                undecomposed_.factor_nonzeros *
                                (spread_factor ? 1. : processes_on_machine);
    }


    template <int dim>
    void
    MethodChoice<dim>::estimate_tfeti(
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const DecompositionParameters                    &parameters,
      const double                                      tolerance,
      const unsigned int                                n_processes)
    {
      for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const fem::ElasticBody<dim> &body = *bodies[b];
        const unsigned int           n_parts =
          parameters.n_subdomains(b, body.triangulation().n_active_cells());
        const std::vector<unsigned int> part = partition_cells(
          body.triangulation(), n_parts, parameters.partitioner, body.name());
        const unsigned int n_pieces =
          *std::max_element(part.begin(), part.end()) + 1;
        std::vector<std::vector<typename DoFHandler<dim>::active_cell_iterator>>
          cells(n_pieces);
        for (const auto &cell : body.dof_handler().active_cell_iterators())
          cells[part[cell->active_cell_index()]].push_back(cell);
        for (const auto &subdomain : cells)
        {
          const fem::FactorEstimate::Result result =
            fem::FactorEstimate::analyze(
              cells_pattern(body, subdomain),
              fem::CholmodSolver::Ordering::nested_dissection);
          tfeti_.factor_flops += result.flops;
          tfeti_.factor_nonzeros += result.factor_nonzeros;
        }
        tfeti_.n_subdomains += n_pieces;
      }
      tfeti_.computed = true;
      const double share =
        1. / std::max(1u, std::min(n_processes, tfeti_.n_subdomains));
      const double product =
        solve_seconds_per_nonzero * tfeti_.factor_nonzeros * share;
      tfeti_.setup_seconds =
        tfeti_.factor_flops / subdomain_rate * share + setup_products * product;
      tfeti_.qp_seconds = tfeti_products(tolerance) * product;
      tfeti_.megabytes  = 8e-6 * tfeti_.factor_nonzeros;
    }


    template <int dim>
    double
    MethodChoice<dim>::tfeti_products(const double tolerance)
    {
      // the friction brick with bisection's subdomains of 1,000 cells
      // (doc/benchmarks/tfeti.md, "Partitioner"): 487-587 products at 1e-4,
      // 779-1,031 at 1e-6, independent of the mesh size at fixed H / h
      const double digits = -std::log10(std::clamp(tolerance, 1e-14, 0.1));
      return 160. * digits;
    }


    template <int dim>
    DecompositionParameters::Method
    MethodChoice<dim>::method() const
    {
      return method_;
    }


    template <int dim>
    const typename MethodChoice<dim>::Estimate &
    MethodChoice<dim>::undecomposed() const
    {
      return undecomposed_;
    }


    template <int dim>
    const typename MethodChoice<dim>::Estimate &
    MethodChoice<dim>::tfeti() const
    {
      return tfeti_;
    }


    template <int dim>
    std::string
    MethodChoice<dim>::description() const
    {
      using Method = DecompositionParameters::Method;
      std::ostringstream line;
      line << std::setprecision(3) << "Decomposition: automatic chose "
           << (method_ == Method::tfeti ? "TFETI" : "the undecomposed dual")
           << " (" << reason_ << ")";
      if (undecomposed_.computed)
        line << "; estimates: undecomposed " << undecomposed_.seconds()
             << " s (pattern analysis " << undecomposed_.factor_flops * 1e-9
             << " GFlop, " << undecomposed_.megabytes << " MB on this machine)"
             << ", TFETI " << tfeti_.seconds() << " s (" << tfeti_.n_subdomains
             << " subdomains, factors " << tfeti_.factor_flops * 1e-9
             << " GFlop, " << tfeti_.megabytes << " MB, set-up "
             << tfeti_.setup_seconds << " s, QP " << tfeti_.qp_seconds << " s)";
      return line.str();
    }


    template class MethodChoice<2>;
    template class MethodChoice<3>;
  } // namespace decomposition
} // namespace dualcontact
