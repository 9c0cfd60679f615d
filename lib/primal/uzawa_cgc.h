#pragma once

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <contact/contact_discretization.h>
#include <contact/coulomb_fixed_point.h>
#include <fem/elastic_body.h>
#include <primal/preconditioner.h>
#include <primal/primal_parameters.h>
#include <qp/cgc.h>
#include <qp/linear_inequalities.h>
#include <qp/solver_statistics.h>

#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace primal
  {
    /**
     * The primal method of Kestranek & Nedoma (1996, section 5): the saddle
     * point of
     *   f(u, mu) = 1/2 u'Ku - u'f + mu' G u,   B_N u <= c,  |mu_i| <= 1,
     * by Uzawa's algorithm over the friction multipliers mu, each step a QP
     * in u with the non-penetration rows solved by CGC (qp::CGC, sections
     * 6-7) with the chosen preconditioner and version (sections 8-10):
     *   u^k = argmin_{B_N u <= c} f(u, mu^k),
     *   mu^{k+1} = Pi(mu^k + rho G u^k).
     *
     * The discrete problem is exactly the one the dual solvers solve
     * (contact::DualProblem): same K (block diagonal over the bodies,
     * condensed), load f, B_N, c = gap - B_N u_D, B_T and tangential offset
     * o_T = B_T u_D; the Tresca friction functional sum_i psi_i |B_T,i u +
     * o_T,i| is max_{|mu_i| <= 1} sum_i mu_i psi_i (B_T,i u + o_T,i), so G =
     * diag(psi) B_T (plus the constant offset), with the nodal slip bound
     * psi_i = g w_i.  In 3D mu_i is a vector of the unit disc, and the
     * orthotropic ellipse is diag(psi_1, psi_2) applied to it.  The
     * multipliers map to the dual's: lambda_N = the CGC multipliers of the
     * non-penetration rows, lambda_T = psi mu.
     *
     * Coulomb pairs: a fixed point over Tresca problems with psi = mu_F
     * lambda_N, starting from the frictionless solution, each Uzawa loop
     * warm started (multipliers and displacements) from the previous one.
     *
     * The first CGC solve starts from u = 0 (report, remark 7.1; if some
     * c_i < 0, from the least-norm u with B_N u = min(c, 0)); later Uzawa
     * iterations start from the previous u.
     */
    template <int dim>
    class UzawaCGC
    {
    public:
      using VectorType  = dealii::Vector<double>;
      using OuterRecord = typename qp::CGC<VectorType>::OuterRecord;

      struct Result
      {
        /** Distributed displacements of every body. */
        std::vector<VectorType> displacements;
        /** Multipliers in the dual layout [lambda_N; lambda_T]. */
        VectorType lambda;
        /** The friction multipliers mu (|mu| <= 1), (dim - 1) per frictional
         * contact node, or per slave face with `Friction multipliers = per
         * edge' (in the order of ContactDiscretization::faces(), faces of
         * frictionless pairs left out). */
        VectorType friction_multipliers;
        /** Nodal slip bounds psi [N; N/m in 2D] of the frictional nodes
         * (second: along the second tangent, 3D), as
         * contact::DualProblem::set_slip_bounds() takes them. */
        std::vector<double> slip_bounds_first, slip_bounds_second;
        bool                converged = false;
        std::string         reason;

        /** Uzawa iterations over all Tresca problems. */
        unsigned int uzawa_iterations = 0;
        /** Tresca problems solved (1, or the Coulomb fixed-point
         * iterations including the frictionless start). */
        unsigned int n_tresca = 0;
        /** The step rho of the last Tresca problem and ||G K^{-1} G'||. */
        double rho       = 0.;
        double lipschitz = 0.;
        /** max |mu^{k+1} - mu^k| per Uzawa iteration. */
        std::vector<double> mu_changes;

        /** The first CGC solve (from u = 0): statistics and its outer
         * iterations (the report's tables 11.3-11.10). */
        qp::SolverStatistics     first_cgc;
        std::vector<OuterRecord> first_outer;
        /** Totals over every CGC solve. */
        unsigned int  n_cgc_solves           = 0;
        unsigned long total_inner_iterations = 0;
        unsigned long total_outer_iterations = 0;
        /** The worst relative CGC criterion of the CGC solves. */
        double worst_cgc_criterion = 0.;

        /** Wall times [s]: preconditioner set-up (factorization, PCG-1
         * transformed rows), all CGC solves, the whole solve(). */
        double setup_time = 0.;
        double cgc_time   = 0.;
        double total_time = 0.;
        /** Name of the preconditioner ("none", "P-DIAG", ...) and version. */
        std::string preconditioner;
        std::string version;
        /** Diagonal shift of incomplete Cholesky (0: none needed). */
        double ic_shift = 0.;
        /** Non-penetration rows (contact nodes with an unknown in their
         * row) and unknowns of the QP. */
        unsigned int n_constraints = 0;
        unsigned int n_unknowns    = 0;

        /** Everything above but the fields, as a JSON object (statistics.json
         * of the app, `contact/primal'). */
        std::string
        to_json() const;
      };

      UzawaCGC(const std::vector<const fem::ElasticBody<dim> *> &bodies,
               const contact::ContactDiscretization<dim>        &contact,
               const PrimalParameters                           &parameters,
               const contact::CoulombParameters &coulomb_parameters = {});
      ~UzawaCGC();

      /** Solve (never throws for a solve that fails to converge: see
       * Result::converged and reason). */
      Result
      solve();

      /** The block-diagonal stiffness matrix of all bodies (condensed). */
      const dealii::SparseMatrix<double> &
      stiffness_matrix() const;

    private:
      /** One Tresca problem by Uzawa for the bounds psi_ (mu_, u_ warm). */
      bool
      uzawa(Result &result);
      /** u_ := argmin f(u, mu_) subject to B_N u <= c by CGC. */
      qp::SolverStatistics
      solve_qp(Result &result);
      /** ||G K^{-1} G'|| by power iteration with the complete Cholesky. */
      double
      estimate_lipschitz();
      /** Set psi_ from the pairs' laws; Coulomb from @p lambda_N. */
      void
      update_slip_bounds(const VectorType *lambda_N);
      /** dst_m = sum_r c_{m,r} (B_T,fric u + o_T)_r, one entry per
       * friction multiplier m (G u = psi dst); without the offset o_T if
       * @p with_offset is false. */
      void
      tangential_slip(const VectorType &u,
                      VectorType       &dst,
                      const bool        with_offset = true) const;
      /** dst += B_T,fric' C' w (C the multiplier-to-row weights). */
      void
      add_tangential_transpose(const VectorType &w, VectorType &dst) const;
      /** Per frictional row r: sum_m c_{m,r} v_m. */
      VectorType
      to_rows(const VectorType &v) const;

      std::vector<const fem::ElasticBody<dim> *> bodies_;
      const contact::ContactDiscretization<dim> &contact_;
      PrimalParameters                           parameters_;
      contact::CoulombParameters                 coulomb_parameters_;

      dealii::SparsityPattern      pattern_;
      dealii::SparseMatrix<double> K_;
      VectorType                   load_;
      /** Non-penetration rows (zero rows skipped) and the node of each. */
      std::shared_ptr<qp::LinearInequalities> rows_;
      std::vector<unsigned int>               row_node_;
      /** PCG-1: the rows of A E^{-T}. */
      std::shared_ptr<qp::LinearInequalities> transformed_rows_;
      std::unique_ptr<Preconditioner>         preconditioner_;
      std::unique_ptr<Preconditioner>         cholesky_; ///< for rho
      bool                                    pcg1_ = false;

      std::vector<unsigned int> frictional_nodes_;
      std::vector<int>          frictional_index_;
      /** Per friction multiplier m: the frictional rows it acts on,
       * (dim - 1) j + k for node j and tangent k, with their weights
       * c_{m,r} (per node: the row itself with 1; per edge: the face's
       * nodes with w_{f,i}); (dim - 1) consecutive multipliers form the
       * vector projected onto the unit ball. */
      std::vector<std::vector<std::pair<unsigned int, double>>> mult_rows_;
      /** Per multiplier: the frictional node index j (per node) or the
       * pair of the face (per edge), and the tangent k. */
      std::vector<unsigned int> mult_source_;
      bool                      per_edge_ = false;
      /** psi per friction multiplier: g w_i per node, g per edge. */
      VectorType psi_;
      /** Friction multipliers mu, (dim - 1) per node or per face. */
      VectorType mu_;
      /** Current displacements (condensed) and, for PCG-1, y = E'u. */
      VectorType u_, y_;
      bool       started_ = false;
      /** Multipliers of the rows at the last CGC solution. */
      std::vector<std::pair<dealii::types::global_dof_index, double>>
        multipliers_;
    };
  } // namespace primal
} // namespace dualcontact
