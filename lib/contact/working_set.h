#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/vector.h>

#include <contact/dual_formulation.h>
#include <qp/problem.h>

#include <string>
#include <utility>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * Parameters of the working set over the normal contact rows,
     * subsection `Dual problem / Working set`.
     */
    struct WorkingSetParameters
    {
      /** Solve on the rows that can close first (see WorkingSet). */
      bool enabled = true;
      /**
       * A normal row is kept when its bound c_i is within
       * reach_factor * delta of the smallest bound of its pair (or of 0),
       * delta the largest normal displacement the loads and prescribed
       * displacements give the slave nodes without contact [-].
       */
      double reach_factor = 10.;
      /** Limit on the solve / check / add-back rounds of one QP. */
      unsigned int max_rounds = 20;

      /**
       * Whether the rows that rounds of rising precision find separated are
       * dropped (see WorkingSet).  Off by default: it cuts the iterations
       * of TFETI 2 to 6 times where separated rows dominate, but doubles
       * them on the friction brick (doc/benchmarks/tfeti.md, "Separated
       * rows").
       */
      bool drop_separated_rows = false;
      /**
       * Relative tolerance of the first round that looks for separated rows
       * (the solver's own tolerance where that is larger) [-].
       */
      double separation_tolerance = 0.1;
      /**
       * Factor from one round's tolerance to the next while separated rows
       * are looked for (down to the QP solver's tolerance) [-].
       */
      double separation_reduction = 0.1;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };


    /** What the working set did for one QP (statistics.json, the log). */
    struct WorkingSetRecord
    {
      /** False: the QP was solved once, on all rows. */
      bool used = false;
      /** Normal rows of the dual. */
      unsigned int n_normal_rows = 0;
      /** Normal rows dropped before the first solve. */
      unsigned int n_dropped = 0;
      /** Dropped rows added back because the displacement violated them. */
      unsigned int n_added = 0;
      /**
       * Kept normal rows dropped because a round found their node separated
       * (WorkingSetParameters::drop_separated_rows).
       */
      unsigned int n_separated = 0;
      /** Normal rows still dropped at the end (each checked: no penetration).
       */
      unsigned int n_dropped_final = 0;
      /** QPs solved on the working set. */
      unsigned int n_rounds = 0;
      /** The reach [m] below which rows were kept. */
      double reach = 0.;
      /** Why the working set was given up for all rows (empty: it was not). */
      std::string fall_back;
    };


    /**
     * The outer working-set loop over the normal contact rows of a dual.
     *
     * Why: the dual's linear term d = B K^# f - c holds the bounds c_i of
     * every slave node, also of those that the loads cannot bring into
     * contact.  For a stiff body (F ~ 1/E) or a body far from its master
     * (c ~ 10 m) these rows make ||d|| many orders larger than the part of d
     * that decides the solution, so the solvers' relative stopping tests
     * (||g^P|| <= tol ||b||) and SMALSE-M's precision control (eta ~ ||b||)
     * are far too loose for the rows in contact: the floating cylinder
     * fails from E = 1e4 MPa on, the 99 m gap at any stiffness
     * (doc/stability.md).
     *
     * What: a normal row i of pair p is dropped (lambda_N,i = 0) when
     *   c_i > max(min_{j in p} c_j, 0) + reach,
     *   reach = reach_factor * (max_j |B_N K^# f|_j + max_j |offset_j|),
     * the displacement of the slave nodes under the loads alone (no
     * contact) plus the prescribed normal displacements.  Tangential rows
     * and the non-contact multipliers of a dual are always kept (a Tresca
     * bound acts on separated nodes too).  The QP on the kept rows is then
     * the dual's QP with the dropped multipliers fixed at zero; with
     * equality constraints G lambda = e its linear term is shifted by the
     * least-squares G'beta (exact: lambda'G'beta = e'beta is constant on
     * the feasible set), which takes the rigid-body part of the gaps (a
     * uniform 99 m) out of it, then a multiple of G_W'e is added back so
     * that ||b_W|| = max(||b_W||, min(||e||, ||b||)) (exact too): the
     * solvers' relative tests then refer to the loads where far gaps
     * dominate b, and are never looser than the whole QP's.
     *
     * Exact on the whole problem: after each solve the displacement is
     * recovered and every dropped row checked, B_N,i u <= c_i; rows that
     * are violated are added back and the QP solved again (warm started),
     * until none is.  The final multipliers then satisfy the KKT conditions
     * of the whole dual: the dropped rows are feasible with lambda_N,i = 0.
     *
     * Separated rows (TFETI): the rounds start at a loose tolerance (0.1)
     * and tighten by a factor (0.1) towards the QP's own; after each, the
     * normal rows with lambda_N,i = 0 whose node is open in the recovered
     * displacement are dropped too (a row once added back stays), and once
     * a round that moved drops or adds nothing, the next is the last, at
     * the QP's tolerance, checked as above.  Why: a row at its bound cannot
     * move, but its column of G = R'B' still ties the rigid-body modes of its
     * subdomain to it, so on the free multipliers SMALSE-M's projector and
     * penalty describe the wrong equality; with every contact row at its bound
     * the brick of doc/benchmarks/tfeti.md ("Numerical scalability") needs 343
     * inner iterations with those columns and 37 without.  Dropping the
     * rows takes their columns out of G_W, which is made orthonormal again:
     * that brick at 128 subdomains needs 220 inner iterations instead of
     * 1,246, 3D Hertz at 1e-8 2,671 instead of 5,251; the friction brick
     * 8,647 instead of 4,511, hence off by default (doc/benchmarks/tfeti.md,
     * "Separated rows").
     */
    template <int dim>
    class WorkingSet
    {
    public:
      using VectorType = dealii::Vector<double>;

      /** Selects the initial rows from the (scaled) QP @p full of @p dual. */
      WorkingSet(const DualFormulation<dim>    &dual,
                 const qp::Problem<VectorType> &full,
                 const WorkingSetParameters    &parameters);

      /** Whether some row was dropped (else solve @p full as it is). */
      bool
      drops_rows() const;

      /** The QP on the kept multipliers (valid while *this lives). */
      qp::Problem<VectorType>
      reduced_problem() const;

      /** The kept entries of @p whole. */
      void
      gather(const VectorType &whole, VectorType &kept) const;
      /** @p whole with the kept entries from @p kept, the dropped ones 0. */
      void
      scatter(const VectorType &kept, VectorType &whole) const;

      /**
       * Adds every dropped normal row that the displacements @p u (per
       * body, constraints distributed) violate; returns their number.
       */
      unsigned int
      add_violated_rows(const std::vector<dealii::Vector<double>> &u);

      /**
       * Whether the rows found separated in rounds are dropped
       * (WorkingSetParameters::drop_separated_rows).
       */
      bool
      separates_rows() const;

      /**
       * Drops every kept normal row whose multiplier in @p lambda (all
       * multipliers) is 0 and whose node the displacements @p u leave
       * open; returns their number.
       */
      unsigned int
      drop_separated_rows(const VectorType                          &lambda,
                          const std::vector<dealii::Vector<double>> &u);

      const WorkingSetRecord &
      record() const;
      WorkingSetRecord &
      record();

    private:
      void
      select_rows();
      void
      update_index();
      /**
       * Gap c_i - B_N,i u of normal row @p i in the displacements @p u (per
       * body), and the size of the terms it sums (for its rounding).
       */
      std::pair<double, double>
      normal_gap(const unsigned int                         i,
                 const std::vector<dealii::Vector<double>> &u) const;

      const DualFormulation<dim>    &dual_;
      const qp::Problem<VectorType> &full_;
      WorkingSetParameters           parameters_;
      /** Per multiplier: whether it is in the working set. */
      std::vector<bool> kept_;
      /** Per normal row: added back once, so never dropped again. */
      std::vector<bool> locked_;
      /** The kept multipliers, in order. */
      std::vector<unsigned int> index_;
      WorkingSetRecord          record_;
    };
  } // namespace contact
} // namespace dualcontact
