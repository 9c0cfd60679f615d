#pragma once

#include <decomposition/decomposition_parameters.h>
#include <fem/elastic_body.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace decomposition
  {
    /**
     * `Decomposition/Method = automatic': the undecomposed dual or TFETI,
     * whichever is estimated to finish first (and fits in memory), decided
     * before either is built.
     *
     * Both estimates start from CHOLMOD's symbolic analysis
     * (fem::FactorEstimate), which gives a factor's nonzeros and flops
     * exactly from the sparsity pattern alone:
     *  - undecomposed: every body's condensed stiffness pattern analysed
     *    as the stiffness solver orders it; time = flops / R_global, the
     *    dual's set-up (the Schur block of the contact dofs, F) taken in by
     *    a calibrated factor (it scales like the factorization on the
     *    benchmark scenes); memory = the factors times the processes on the
     *    machine that hold a copy.
     *  - TFETI: every body cut as TFETIDual will cut it (partition_cells()
     *    with the same parameters), every subdomain's pattern analysed under
     *    nested dissection (the subdomain solver's ordering); set-up = sum
     *    of the subdomains' flops / R_subdomain, the QP = products(tol) x
     *    (sum of the subdomains' factor nonzeros) x the time per nonzero
     *    of a forward and backward solve (memory-bound), both divided by
     *    the processes (the subdomains are spread over them).
     * The rates and the products per tolerance are measured on this
     * project's machines (doc/benchmarks/tfeti.md, "Automatic choice");
     * they decide where the two cross, not the seconds a run will take.
     * Scenes much larger than the memory limit (the old size estimate,
     * DecompositionParameters::estimate_factor_megabytes(), above 4 times
     * it) are decomposed without an analysis (its pattern alone would take
     * gigabytes).
     */
    template <int dim>
    class MethodChoice
    {
    public:
      /** The estimated cost of one method. */
      struct Estimate
      {
        bool         computed        = false;
        double       setup_seconds   = 0; ///< factorizations (and F) [s]
        double       qp_seconds      = 0; ///< the QP's products [s]
        double       megabytes       = 0; ///< factors on this machine [MB]
        double       factor_flops    = 0; ///< all factorizations [flop]
        double       factor_nonzeros = 0; ///< all factors [nonzeros]
        unsigned int n_subdomains    = 0; ///< TFETI: the subdomains
        double
        seconds() const
        {
          return setup_seconds + qp_seconds;
        }
      };

      /**
       * The choice for @p bodies (set up: dofs distributed, constraints
       * made) on @p n_processes processes (@p processes_on_machine of them
       * on this machine) with the QP's relative @p tolerance.
       * @p spread_factor: the undecomposed stiffness solver holds one
       * factor spread over the processes (MUMPS) rather than one copy per
       * process (CHOLMOD).  Collective under MPI: every process gets the
       * first one's choice.
       */
      MethodChoice(const std::vector<const fem::ElasticBody<dim> *> &bodies,
                   const DecompositionParameters                    &parameters,
                   const double                                      tolerance,
                   const unsigned int n_processes,
                   const unsigned int processes_on_machine,
                   const bool         spread_factor);

      DecompositionParameters::Method
      method() const;
      const Estimate &
      undecomposed() const;
      const Estimate &
      tfeti() const;
      /** One line for the log: the choice and both estimates. */
      std::string
      description() const;

      /** The QP's Hessian products TFETI needs for @p tolerance (measured:
       * doc/benchmarks/tfeti.md). */
      static double
      tfeti_products(const double tolerance);

    private:
      void
      estimate_undecomposed(
        const std::vector<const fem::ElasticBody<dim> *> &bodies,
        const unsigned int                                processes_on_machine,
        const bool                                        spread_factor);
      void
      estimate_tfeti(const std::vector<const fem::ElasticBody<dim> *> &bodies,
                     const DecompositionParameters &parameters,
                     const double                   tolerance,
                     const unsigned int             n_processes);

      DecompositionParameters::Method method_;
      Estimate                        undecomposed_;
      Estimate                        tfeti_;
      double                          memory_limit_;
      std::string                     reason_;
    };
  } // namespace decomposition
} // namespace dualcontact
